# simlab package gradescope: the archive's setup.sh builds it from scratch, and its run_autograder grades a
# submission laid out as Gradescope lays it out into a valid results.json, hidden tests marked hidden.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

run_capture package "$SIMLAB" package gradescope apple -o autograder.zip
check "package gradescope succeeds" test "$(status_of package)" -eq 0
check "setup.sh and run_autograder are at the root of the archive" \
  bash -c "unzip -Z1 autograder.zip | grep -qx setup.sh && unzip -Z1 autograder.zip | grep -qx run_autograder"
check "the archive holds the hidden tests" bash -c "unzip -Z1 autograder.zip | grep -qx assignments/apple/grading/hidden.cpp"
check "and no solutions (but the worked example project's)" \
  bash -c "! unzip -Z1 autograder.zip | grep '^solutions/.' | grep -qv '^solutions/biosim/'"

root=$PWD/autograder
mkdir -p "$root/source" "$root/submission" "$root/results"
unzip -q autograder.zip -d "$root/source"

# Gradescope's default base image is Ubuntu 22.04, whose CMake is too old: setup.sh says so in one line, at once.
printf 'ID=ubuntu\nVERSION_ID="22.04"\nPRETTY_NAME="Ubuntu 22.04.4 LTS"\n' >jammy-os-release
run_capture jammy env SIMLAB_OS_RELEASE=$PWD/jammy-os-release "$root/source/setup.sh"
check "on Ubuntu 22.04 setup.sh stops at once, in one line naming the image and the one to choose" \
  bash -c "test $(status_of jammy) -eq 1 && test \$(wc -l <jammy.err) -eq 1 &&
    grep -q 'base image is Ubuntu 22.04.4 LTS: choose Ubuntu 24.04' jammy.err && test ! -e '$root/source/build'"
check "the archive carries Catch2 2.13's header, for images that ship Catch2 3" \
  bash -c "unzip -Z1 autograder.zip | grep -qx third_party/catch2/catch.hpp"
check "setup.sh installs only what a check needs (no pages, schematics or test tools) and builds the lab's grader alone" \
  bash -c "grep -q 'scripts/setup\" --lean' '$root/source/setup.sh' && grep -q \"^targets='simlab apple_grader'\" '$root/source/setup.sh'"
# Build as on an image without Catch2 2 (Gradescope's Ubuntu 24.04 ships Catch2 3): from the carried header. The
# objects it shares with the build under test come from that build's ccache (tests/smoke/lib.sh, shared_objects).
shared_objects "$root/source"
SIMLAB_SKIP_APT=1 SIMLAB_JOBS=2 SIMLAB_CMAKE_ARGS="-DCMAKE_DISABLE_FIND_PACKAGE_Catch2=ON $shared_objects" \
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
check "run_autograder grades the reference: 100/100 on 13 tests" \
  "$VALIDATE" "$root/results/results.json" --score 100 --max 100 --tests 13
# Gradescope's specification: a hidden test is never shown, and while any test is hidden the student cannot see
# the total. A test with points is never hidden: simlab's hidden tests are shown after the due date.
check "the hidden tests (points) are shown after the due date" \
  test "$(grep -c '"visibility": "after_due_date"' "$root/results/results.json")" -eq 5
check "and no test that carries points is hidden" python3 -c '
import json, sys
tests = json.load(open(sys.argv[1]))["tests"]
sys.exit(any(t["visibility"] == "hidden" and t["max_score"] > 0 for t in tests))' "$root/results/results.json"

rm -rf "$root/submission"/* && cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" "$root/submission/apple.cpp"
grade_submission misnamed
check "a misnamed file is graded, and said to be misnamed" grep -q 'graded apple.cpp; expected NewtonsApple.cpp' "$root/results/results.json"
check "its results.json is valid (the starter: 0)" "$VALIDATE" "$root/results/results.json" --score 0

rm -rf "$root/submission"/* && echo "notes" >"$root/submission/README.txt"
grade_submission missing
check "a submission without a C++ file gets a valid results.json with 0 and the reason" \
  bash -c "'$VALIDATE' '$root/results/results.json' --score 0 && grep -q 'no NewtonsApple.cpp' '$root/results/results.json'"
finish
