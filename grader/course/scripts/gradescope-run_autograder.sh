#!/usr/bin/env bash
# Gradescope runs this for every submission: it grades /autograder/submission on every test of the
# @ASSIGNMENT_NAME@ assignment and writes /autograder/results/results.json.
# AUTOGRADER_ROOT replaces /autograder (for testing).
# (simlab package gradescope writes it from grader/course/scripts/gradescope-run_autograder.sh.)
root=${AUTOGRADER_ROOT:-/autograder}
assignment=@ASSIGNMENT@  # the course's lab's id, or the folder of a lab of one's own in source/
[[ $assignment == */* ]] && assignment=$root/source/$assignment
exec "$root/source/build/bin/simlab" autograde "$assignment" --submission "$root/submission" \
  --results "$root/results/results.json"
