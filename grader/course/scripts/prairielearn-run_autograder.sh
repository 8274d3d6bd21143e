#!/usr/bin/env bash
# PrairieLearn runs this in the grading container for every submission: it grades /grade/student on every
# test of the @ASSIGNMENT_NAME@ assignment, the hidden ones with the judge in this folder, and writes
# /grade/results/results.json.
#   GRADE_ROOT  replaces /grade (for testing)
#   SIMLAB      the simlab command (default: the grading image's)
# (simlab package prairielearn writes it from grader/course/scripts/prairielearn-run_autograder.sh.)
root=${GRADE_ROOT:-/grade}
simlab=${SIMLAB:-/simlab/build/bin/simlab}
assignment=@ASSIGNMENT@
results=$root/results/results.json
mkdir -p "$root/results"
# A results.json that says why nothing was graded, and the end.
not_gradable() {
  printf '{"gradable": false, "score": 0, "message": "The autograder could not grade this submission: %s.", "format_errors": ["%s"]}\n' \
    "$1" "$1" >"$results"
  exit 1
}
[[ -x $simlab ]] || not_gradable "simlab is not in the grading image"
[[ -f $root/tests/judge ]] || not_gradable "the question has no judge of its hidden tests (tests/judge): make it once with scripts/prairielearn-judge, as image/Dockerfile says"
# The hidden tests' judge is root's alone, should the container allow neither bubblewrap nor Landlock.
chmod -R go-rwx "$root/tests" 2>/dev/null
exec "$simlab" autograde "$assignment" --format prairielearn --judge "$root/tests/judge" \
  --submission "$root/student" --results "$results"
