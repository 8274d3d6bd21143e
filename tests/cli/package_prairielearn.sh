# simlab package prairielearn: the question folder PrairieLearn documents (info.json, question.html, tests/), its
# image - no hidden test in it, since anyone may pull it: its sources are the student bundle's, built by
# cli/package-student - the hidden tests' judge made with that build from the question's tests/
# (scripts/prairielearn-judge), and the entry point run in a temporary /grade with it: results.json in
# PrairieLearn's format, with the points simlab check --all gives.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
validate() { python3 "$SOURCE_DIR/tests/tools/validate_platforms.py" "$@"; }
# points FILE: the score of a Gradescope results.json (what simlab check --format json prints)
points() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["score"])' "$1"; }

run_capture package "$SIMLAB" package prairielearn apple -o question --image course/simlab:1 --timeout 240
check "package prairielearn succeeds" test "$(status_of package)" -eq 0
check "info.json is a question PrairieLearn's schema takes, externally graded" validate prairielearn-info question/info.json
check "info.json names the image, the entry point in tests/ and the timeout" python3 -c '
import json, sys
o = json.load(open("question/info.json"))["externalGradingOptions"]
sys.exit(not (o["image"] == "course/simlab:1" and o["entrypoint"] == "/grade/tests/run_autograder" and o["timeout"] == 240))'
check "the entry point is executable" test -x question/tests/run_autograder
check "question.html: the file in an editor, opened on the starter" \
  grep -q '<pl-file-editor file-name="NewtonsApple.cpp" ace-mode="ace/mode/c_cpp" source-file-name="NewtonsApple.cpp">' \
  question/question.html
check "question.html: the grader's results in the submission panel" \
  bash -c "grep -q '<pl-submission-panel>' question/question.html && grep -q '<pl-external-grader-results>' question/question.html"
check "the starter is beside it" cmp question/NewtonsApple.cpp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp"
check "the Dockerfile builds simlab with scripts/setup on Ubuntu 24.04" bash -c "
  grep -qx 'FROM ubuntu:24.04' question/image/Dockerfile &&
  grep -qx 'COPY simlab /simlab' question/image/Dockerfile &&
  grep -q '^RUN .*/simlab/scripts/setup' question/image/Dockerfile && test -x question/image/simlab/scripts/setup"
check "the image's sources hold Catch2 2.13's header and no hidden test" bash -c "
  test -f question/image/simlab/third_party/catch2/catch.hpp &&
  test -z \"\$(find question/image/simlab -name 'hidden*' -o -name 'trade-hidden*')\""
check "and no solutions (but the worked example project's)" \
  bash -c "! find question/image/simlab/solutions -mindepth 1 -maxdepth 1 | grep -qv '/solutions/biosim$'"
check "the hidden tests are in tests/hidden, which PrairieLearn keeps from students" bash -c "
  cmp question/tests/hidden/assignments/apple/grading/hidden.cpp '$SOURCE_DIR/assignments/apple/grading/hidden.cpp' &&
  cmp question/tests/hidden/assignments/apple/grading/trade-hidden.json '$SOURCE_DIR/assignments/apple/grading/trade-hidden.json'"
check "the Dockerfile says how to make the judge once" \
  grep -q 'docker run --rm -v "$PWD/../tests:/grade/tests" course/simlab:1 /simlab/scripts/prairielearn-judge apple /grade/tests' \
  question/image/Dockerfile
check "the default entry point is the image's simlab" grep -q 'SIMLAB:-/simlab/build/bin/simlab' question/tests/run_autograder

run_capture upload "$SIMLAB" package prairielearn apple -o uploaded --upload
check "--upload: the student uploads the file" \
  bash -c "grep -q '<pl-file-upload file-names=\"NewtonsApple.cpp\">' uploaded/question.html && ! test -e uploaded/NewtonsApple.cpp"
run_capture late "$SIMLAB" package prairielearn apple -o late --timeout 601
check "a timeout over PrairieLearn's 600 s is refused in one line" \
  bash -c "test $(status_of late) -ne 0 && test \$(wc -l <late.err) -eq 1"
run_capture again "$SIMLAB" package prairielearn apple -o question
check "a folder that is not empty is refused" bash -c "test $(status_of again) -ne 0 && grep -q 'not empty' again.err"

grade=$PWD/grade
mkdir -p "$grade"
grade_submission() {  # grade_submission NAME: run the entry point on what is in $grade/student
  rm -rf "$grade/results"
  GRADE_ROOT=$grade SIMLAB=$image_simlab "$grade/tests/run_autograder" >"$1.out" 2>"$1.err"
  echo $? >"$1.status"
}

# The image, as its Dockerfile builds it: its sources are the student bundle's (the bundle adds its README and the
# handouts' pages), which cli/package-student builds with its own scripts/setup, from nothing ($FIXTURES/bundle).
image=$FIXTURES/bundle
image_simlab=$image/build/bin/simlab
check "the image's sources are the student bundle's" \
  diff -rq -x build -x README.md -x '*.html' -x '*-reference.svg' question/image/simlab "$image"
check "which builds from them: the image's simlab is there" test -x "$image_simlab"
cp -r question/tests "$grade/tests"
mkdir -p "$grade/student"
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" "$grade/student/"
grade_submission nojudge
check "before the judge is made: not gradable, saying how to make it" bash -c "
  test $(status_of nojudge) -ne 0 &&
  python3 '$SOURCE_DIR/tests/tools/validate_platforms.py' prairielearn '$grade/results/results.json' --gradable no &&
  grep -q 'scripts/prairielearn-judge' '$grade/results/results.json'"
run_capture imagecheck "$image_simlab" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" --all
check "the image's own simlab has no hidden test to run (--all is refused)" \
  bash -c "test $(status_of imagecheck) -ne 0 && grep -q 'hidden tests' imagecheck.err"
run_capture judge "$image/scripts/prairielearn-judge" apple "$grade/tests"
check "scripts/prairielearn-judge makes tests/judge in the image's build, with the hidden tests" \
  bash -c "test $(status_of judge) -eq 0 && test -x '$grade/tests/judge' && grep -q 'wrote .*tests/judge' judge.out"
check "and leaves the image's tree as it found it: no hidden test in it, its own judge without them" bash -c "
  test -z \"\$(find $image -path $image/build -prune -o -name 'hidden*' -print)\" &&
  ! grep -q 'hidden: ' $image/build/judges/apple-judge"

"$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" --all --format json >reference.json
grade_submission reference
check "the entry point grades the reference into a valid results.json: score 1, the points of check --all" \
  validate prairielearn "$grade/results/results.json" --score 1 --points "$(points reference.json)" --max 100 --gradable yes

rm -rf "$grade/student"/* && cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" "$grade/student/apple.cpp"
"$SIMLAB" check apple "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" --all --format json >starter.json
grade_submission misnamed
check "a lone misnamed file is graded, with the points of check --all, and said to be misnamed" bash -c "
  validate() { python3 '$SOURCE_DIR/tests/tools/validate_platforms.py' \"\$@\"; }
  validate prairielearn '$grade/results/results.json' --score 0 --points $(points starter.json) --max 100 --gradable yes &&
  grep -q 'graded apple.cpp; expected NewtonsApple.cpp' '$grade/results/results.json'"
check "hidden tests show no details" python3 -c '
import json, sys
tests = json.load(open(sys.argv[1]))["tests"]
hidden = [t for t in tests if t["name"].startswith("hidden")]
sys.exit(not (hidden and all("hidden test" in t["message"] and t["output"] == "" and "images" not in t for t in hidden)))' \
  "$grade/results/results.json"

rm -rf "$grade/student"/* && echo "notes" >"$grade/student/README.txt"
grade_submission missing
check "no C++ file: not gradable, and why in format_errors" bash -c "
  python3 '$SOURCE_DIR/tests/tools/validate_platforms.py' prairielearn '$grade/results/results.json' --gradable no &&
  grep -q 'no NewtonsApple.cpp' '$grade/results/results.json'"

rm -rf "$grade/student"
grade_submission nothing
check "no submission at all: still a results.json, not gradable" \
  validate prairielearn "$grade/results/results.json" --gradable no

rm -rf "$grade/results"
GRADE_ROOT=$grade SIMLAB=/nonexistent/simlab "$grade/tests/run_autograder" >broken.out 2>&1
check "an image without simlab: a results.json that says so" \
  bash -c "python3 '$SOURCE_DIR/tests/tools/validate_platforms.py' prairielearn '$grade/results/results.json' --gradable no &&
           grep -q 'simlab is not in the grading image' '$grade/results/results.json'"
finish
