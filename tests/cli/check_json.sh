# simlab check --format json: valid Gradescope results.json; full marks for the reference, low for the starter.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

run_capture solution "$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" --format json
check "check exits 0" test "$(status_of solution)" -eq 0
check "the reference's results.json is valid with score = total of the visible tests (76)" \
  "$VALIDATE" solution.out --score 76 --max 76 --tests 8
run_capture all "$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" --format json --all
check "with --all it scores 100 of 100 on 13 tests" "$VALIDATE" all.out --score 100 --max 100 --tests 13

run_capture starter "$SIMLAB" check apple --format json
check "the starter's results.json is valid and scores 0 (under 40 %)" "$VALIDATE" starter.out --score 0 --max 76
check "the starter's report names the missing work" grep -q 'not done yet (NewtonsApple.cpp' starter.out

run_capture text "$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp"
check "the text report ends with the score" grep -q '^Score: 76/76$' text.out
check "and says what is left for the instructor" grep -q '5 hidden tests worth 24 points are left' text.out
check "each test line shows the measured figure" grep -q 'digits, need 10' text.out
finish
