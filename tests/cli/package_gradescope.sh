# simlab package gradescope: the archive's setup.sh builds it from scratch, and its run_autograder grades a
# submission laid out as Gradescope lays it out into a valid results.json, hidden tests marked hidden.
source "$(dirname "$0")/../smoke/lib.sh"

run_capture package "$SIMLAB" package gradescope apple -o autograder.zip
check "package gradescope succeeds" test "$(status_of package)" -eq 0
check "setup.sh and run_autograder are at the root of the archive" \
  bash -c "unzip -Z1 autograder.zip | grep -qx setup.sh && unzip -Z1 autograder.zip | grep -qx run_autograder"
check "the archive holds the hidden tests" bash -c "unzip -Z1 autograder.zip | grep -qx assignments/apple/tests/hidden.cpp"
check "and no solutions (but the worked example project's)" \
  bash -c "! unzip -Z1 autograder.zip | grep '^solutions/.' | grep -qv '^solutions/biosim/'"

root=$PWD/autograder
mkdir -p "$root/source" "$root/submission" "$root/results"
unzip -q autograder.zip -d "$root/source"
check "the archive carries Catch2 2.13's header, for images that ship Catch2 3" \
  bash -c "unzip -Z1 autograder.zip | grep -qx third_party/catch2/catch.hpp"
# Build as on an image without Catch2 2 (Gradescope's Ubuntu 24.04 ships Catch2 3): from the carried header.
SIMLAB_SKIP_APT=1 SIMLAB_JOBS=2 SIMLAB_CMAKE_ARGS=-DCMAKE_DISABLE_FIND_PACKAGE_Catch2=ON \
  "$root/source/setup.sh" >setup.log 2>&1
check "setup.sh builds the autograder from the archive, with the carried Catch2 header" \
  bash -c "test $? -eq 0 && grep -q 'Catch2 2.13: the header in third_party/catch2' setup.log" || tail -20 setup.log

grade_submission() {  # grade_submission NAME: run run_autograder on what is in $root/submission
  rm -f "$root/results/results.json"
  AUTOGRADER_ROOT=$root "$root/source/run_autograder" >"$1.out" 2>"$1.err"
  echo $? >"$1.status"
}

mkdir -p "$root/submission/upload"
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" "$root/submission/upload/"
grade_submission reference
check "run_autograder grades the reference: 100/100 on 12 tests" \
  "$VALIDATE" "$root/results/results.json" --score 100 --max 100 --tests 12
check "hidden tests are marked hidden" test "$(grep -c '"visibility": "hidden"' "$root/results/results.json")" -eq 4

rm -rf "$root/submission"/* && cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" "$root/submission/apple.cpp"
grade_submission misnamed
check "a misnamed file is graded, and said to be misnamed" grep -q 'graded apple.cpp; expected NewtonsApple.cpp' "$root/results/results.json"
check "its results.json is valid (the starter: 0)" "$VALIDATE" "$root/results/results.json" --score 0

rm -rf "$root/submission"/* && echo "notes" >"$root/submission/README.txt"
grade_submission missing
check "a submission without a C++ file gets a valid results.json with 0 and the reason" \
  bash -c "'$VALIDATE' '$root/results/results.json' --score 0 && grep -q 'no NewtonsApple.cpp' '$root/results/results.json'"
finish
