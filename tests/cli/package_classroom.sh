# simlab package github-classroom: the template repository (the student bundle and the workflow), the workflow's
# fields as GitHub Actions and Classroom's reporter read them, and its check step run as written, with this
# build's simlab, on the starter and on the reference: the runner result the reporter decodes, with the points of
# simlab check on the visible tests.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
validate() { python3 "$SOURCE_DIR/tests/tools/validate_platforms.py" "$@"; }
points() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["score"])' "$1"; }

run_capture package "$SIMLAB" package github-classroom apple -o template
check "package github-classroom succeeds" test "$(status_of package)" -eq 0
run_capture alias "$SIMLAB" package classroom apple -o template-by-alias
check "package classroom is the same command, as grade --from classroom names the platform" \
  bash -c "test $(status_of alias) -eq 0 && diff -r template template-by-alias >/dev/null"
workflow=template/.github/workflows/classroom.yml
check "the workflow is what Classroom and its reporter read: two runners, the points earned and the points missed" \
  validate workflow "$workflow" simlab
check "the student's starter, the contract and the build are there" \
  test -f template/starter/apple/NewtonsApple.cpp -a -f template/assignments/apple/contract/NewtonsApple.h \
       -a -f template/CMakeLists.txt -a -x template/scripts/setup
check "no hidden tests, no solutions (but the worked example project's)" bash -c "
  ! test -e template/assignments/apple/grading/hidden.cpp &&
  ! find template/solutions -mindepth 1 -maxdepth 1 | grep -qv '/solutions/biosim$'"
check "committed as a repository, it keeps Catch2 2.13's header (Ubuntu 24.04 ships Catch2 3)" bash -c "
  cd template && git init -q && git add -A && git ls-files | grep -qx third_party/catch2/catch.hpp &&
  git ls-files | grep -qx .github/workflows/classroom.yml"
check "each push installs only what a check needs and builds simlab with the lab's grader alone, through ccache" \
  python3 - "$workflow" <<'PY'
import sys, yaml
steps = yaml.safe_load(open(sys.argv[1]))["jobs"]["run-autograding-tests"]["steps"]
runs = "\n".join(str(s.get("run", "")) for s in steps)
assert "scripts/install-deps --lean" in runs and "ccache" in runs, runs
assert 'SIMLAB_TARGETS="simlab apple_grader"' in runs and "SIMLAB_SKIP_APT=1" in runs, runs
caches = [s for s in steps if str(s.get("uses", "")).startswith("actions/cache@")]
assert len(caches) == 1 and caches[0]["with"]["path"] == "build/ccache", caches
names = [s.get("name") for s in steps]
assert names.index(caches[0]["name"]) < next(i for i, s in enumerate(steps) if "SIMLAB_TARGETS" in str(s.get("run", "")))
PY
check "the README says the points are a self-check, not the grade" grep -q 'They are a self-check, not your grade' template/README.md

# The check step, as the workflow runs it, in the template with build/bin/simlab this build's simlab.
python3 -c '
import sys, yaml
doc = yaml.safe_load(open(sys.argv[1]))
step = [s for s in doc["jobs"]["run-autograding-tests"]["steps"] if s.get("id") == "simlab"][0]
open("step.sh", "w").write(step["run"])' "$workflow"
run_step() {  # run_step NAME: the step's two results, decoded as the reporter decodes them, into NAME-earned.json and NAME-missed.json
  rm -f "$work/output"
  (cd template && RUNNER_TEMP=$work GITHUB_OUTPUT=$work/output bash -e "$work/step.sh") >"$1.out" 2>"$1.err"
  echo $? >"$1.status"
  for runner in earned missed; do sed -n "s/^$runner=//p" "$work/output" | base64 -d >"$1-$runner.json"; done
}
mkdir -p template/build/bin
ln -s "$SIMLAB" template/build/bin/simlab
visible_max=$(python3 -c '
import json, sys
print(sum(t["max_score"] for t in json.load(open(sys.argv[1]))["tests"]))' <("$SIMLAB" check apple "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" --format json))

"$SIMLAB" check apple "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" --format json >check-starter.json
run_step starter
check "the step runs on the starter and writes earned= and missed= to GITHUB_OUTPUT" test "$(status_of starter)" -eq 0
check "its results are runner results: the starter's points on the visible tests, as simlab check gives them" \
  validate classroom starter-earned.json starter-missed.json --points "$(points check-starter.json)" --max "$visible_max" --status fail

cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" template/starter/apple/NewtonsApple.cpp
"$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" --format json >check-reference.json
run_step reference
check "the reference passes every visible test, with the points of simlab check" \
  validate classroom reference-earned.json reference-missed.json --points "$(points check-reference.json)" --max "$visible_max" --status pass
check "each test says how to run it alone" grep -q 'build/bin/simlab check apple starter/apple/NewtonsApple.cpp --test' reference-earned.json

# Partial credit (the trade test earns part of its points): the reporter's table and the points Classroom records
# agree, both simlab check's score.
"$CORPUS" materialize apple "$SOURCE_DIR/tests/corpus/apple/trade-dearer-method.toml" --out cases >/dev/null
cp cases/trade-dearer-method/NewtonsApple.cpp template/starter/apple/NewtonsApple.cpp
"$SIMLAB" check apple cases/trade-dearer-method/NewtonsApple.cpp --format json >check-partial.json
run_step partial
check "partial credit: the table and the recorded points agree, both $(points check-partial.json) of $visible_max" \
  bash -c "python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))[\"score\"]; sys.exit(0 if s != int(s) else 1)' check-partial.json &&
    python3 '$SOURCE_DIR/tests/tools/validate_platforms.py' classroom partial-earned.json partial-missed.json \
      --points $(points check-partial.json) --max $visible_max --status fail"

rm template/build/bin/simlab
run_step unbuilt
check "simlab not built: the step still hands the reporter a result, an error worth the visible points" \
  validate classroom unbuilt-earned.json unbuilt-missed.json --points 0 --max "$visible_max" --status error

run_capture again "$SIMLAB" package github-classroom apple -o template
check "a folder that is not empty is refused" bash -c "test $(status_of again) -ne 0 && grep -q 'not empty' again.err"
finish
