# simlab grade on a class: killed with -9 mid-batch and run again, it regrades only what was unfinished and the
# gradebook has exactly one row per student; a changed file is regraded alone; --only replaces one row; missing
# and misnamed files are named statuses; JUnit, feedback and summary are written.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

cp -r "$BIN_DIR/../sample-class/apple" class
mkdir class/missing && echo "my notes" >class/missing/README.txt
mkdir class/misnamed && cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/misnamed/apple.cpp
students=$(ls class | wc -l)
rows() { tail -n +2 grades/gradebook.csv | cut -d, -f1 | sort; }
expected_score() { sed -n 's/^score = //p' "$SOURCE_DIR/tests/corpus/apple/$1.toml"; }

"$SIMLAB" grade apple class --out grades --jobs 2 >first.out 2>&1 &
batch=$!
for _ in $(seq 1 600); do  # until a few students are done
  [[ -f grades/gradebook.csv && $(rows | wc -l) -ge 3 ]] && break
  sleep 0.05
done
kill -9 $batch
wait $batch 2>/dev/null
finished=$(rows | wc -l)
check "the batch was killed part-way ($finished of $students finished)" test "$finished" -ge 3 -a "$finished" -lt "$students"
check "the gradebook after kill -9 has one row per finished student, none twice" test "$(rows | uniq -d | wc -l)" -eq 0

run_capture second "$SIMLAB" grade apple class --out grades --jobs 2
check "the rerun succeeds (kill -9 left no lock behind)" test "$(status_of second)" -eq 0
# While another simlab writes into the same folder (here flock(1) holds its lock), a second one stops at once.
run_capture locked flock grades/.simlab-lock "$SIMLAB" grade apple class --out grades --jobs 2
check "a second simlab on the same --out stops in one line, grading nothing" \
  bash -c "test $(status_of locked) -eq 2 && test \$(wc -l <locked.err) -eq 1 && grep -q 'another simlab is writing into grades' locked.err"
check "it reuses what had finished ($finished unchanged)" test "$(grep -c '(unchanged)' second.out)" -eq "$finished"
check "the gradebook now has exactly one row per student" test "$(rows | wc -l)" -eq "$students" -a "$(rows | uniq -d | wc -l)" -eq 0
for case in reference starter gravity-up infinite-loop compile-error; do
  check "$case scores $(expected_score $case)" grep -q "^$case,$(expected_score $case),100," grades/gradebook.csv
done
check "a folder without the file is 'missing file' with 0" grep -q '^missing,0,100,missing file,' grades/gradebook.csv
check "a lone file of another name is graded as 'misnamed file'" grep -q '^misnamed,100,100,misnamed file,' grades/gradebook.csv

cp grades/gradebook.csv before.csv
echo "// a last-minute comment" >>class/gravity-up/NewtonsApple.cpp
run_capture changed "$SIMLAB" grade apple class --out grades --jobs 2
student_lines() { grep -E '^  [a-z0-9-]+ +[0-9.]+/100 ' "$1"; }
check "after one file changes, only that student is regraded" test "$(student_lines changed.out | grep -vc '(unchanged)')" -eq 1
check "the gradebook is unchanged (the comment changes no score)" cmp -s before.csv grades/gradebook.csv

# A kept record edited by hand (a test the rubric does not hold, worth 1000) is damaged: that student is graded
# again, and the gradebook keeps the score the file earns.
python3 - grades/students/starter/record.json <<'PY'
import json, sys
record = json.load(open(sys.argv[1]))
made_up = dict(record["tests"][0], name="a test nobody wrote", score=1000, max_score=1000, credit=1)
record["tests"].append(made_up)
json.dump(record, open(sys.argv[1], "w"))
PY
run_capture edited "$SIMLAB" grade apple class --out grades --jobs 2
check "a kept record naming a test the rubric lacks is graded again" \
  bash -c "student_lines() { grep -E '^  [a-z0-9-]+ +[0-9.]+/100 ' \"\$1\"; }; student_lines edited.out | grep -v '(unchanged)' | grep -q '^  starter '"
check "and the gradebook keeps the score the file earns" cmp -s before.csv grades/gradebook.csv

# A damaged results.json of a student kept as graded is written again from the student's record.
echo '{"score": 100' >grades/students/starter/results.json
run_capture only "$SIMLAB" grade apple class --out grades --only reference --junit junit.xml
check "a kept student's damaged results.json is written again from the record" \
  python3 -c 'import json, sys; sys.exit(json.load(open("grades/students/starter/results.json"))["score"] != 0)'
check "--only grades just that student, and says so" bash -c "test $(student_lines only.out | wc -l) -eq 1 && grep -q '^1 graded, 0 up to date and kept, [0-9]* not asked for (--only) and kept$' only.out"
check "--only keeps every other row as it was" cmp -s before.csv grades/gradebook.csv
run_capture unknown "$SIMLAB" grade apple class --out grades --only nobody
check "--only with an unknown student is an error" grep -q "no student 'nobody'" unknown.err

check "each student has results.json and feedback.md" test "$(ls grades/students/*/results.json grades/students/*/feedback.md | wc -l)" -eq $((2 * students))
check "every results.json is valid" bash -c "for f in grades/students/*/results.json; do '$VALIDATE' \$f >/dev/null || exit 1; done"
check "feedback says how to reproduce a failed test" grep -q 'Reproduce: `simlab check apple NewtonsApple.cpp --test "the integrator is the one asked for' grades/students/segfault/feedback.md
check "feedback keeps hidden tests' details hidden" grep -q 'A hidden test' grades/students/typed-in-answer/feedback.md
check "summary.csv has a row per test" test "$(($(wc -l <grades/summary.csv) - 1))" -eq 13
check "the summary gives the pass rate and the spread of digits" grep -q '^"*y at the final time has the target accuracy digits"*,visible,15,' grades/summary.csv
check "--junit writes one test suite per student" test "$(grep -c '<testsuite ' junit.xml)" -eq "$students"
check "with the crash as an error" grep -q 'type="crashed"' junit.xml
finish
