# What a person grades, and what a regrade keeps: simlab grade writes manual.csv with a pending row per student and
# manual item; the points an instructor types there reach the gradebook, results.json, the feedback pages,
# report.html and the Canvas export, and survive a regrade, which runs no student code for them; a change of a
# test's points re-scores the recorded verdicts without running code again; each student keeps a history of
# grades; a manual.csv with a mistake stops simlab in one line before anything changes.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
cell() { python3 -c 'import csv,sys; print(list(csv.reader(open(sys.argv[1])))[int(sys.argv[2])][int(sys.argv[3])])' "$@"; }
history_lines() { wc -l <"grades/students/$1/history.jsonl"; }
last_why() { tail -1 "grades/students/$1/history.jsonl" | python3 -c 'import json,sys; print(json.load(sys.stdin)["why"])'; }
item="the write-up explains the step size"

# The apple's rubric with an item graded by hand.
cp "$SOURCE_DIR/assignments/apple/grading/rubric.toml" rubric.toml
printf '\n[[manual]]\nname = "%s"\npoints = 20\n' "$item" >>rubric.toml
mkdir -p class/ada class/bob
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/ada/
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" class/bob/
"$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml >first.out 2>&1
printf 'student,item,points,comment,file\nada,%s,,,\nbob,%s,,,\n' "$item" "$item" >expected-sheet.csv
check "graded; manual.csv has a pending row per student and item" cmp -s expected-sheet.csv grades/manual.csv
check "the gradebook says pending, and counts every point there is (120)" \
  bash -c "test '$(cell grades/gradebook.csv 1 2)' = 120 && test '$(cell grades/gradebook.csv 1 17)' = pending"
check "each student's history has its first grade" \
  bash -c "test $(history_lines ada) -eq 1 && test '$(last_why ada)' = 'first graded'"

# The instructor fills in ada's points; the regrade keeps every record and runs nothing.
printf 'student,item,points,comment\nada,%s,15,"the step, not the tolerance"\nbob,%s,,\n' "$item" "$item" >grades/manual.csv
"$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml >manual.out 2>&1
check "the regrade runs no code (both unchanged), and keeps the points typed" \
  bash -c "test \$(grep -c '(unchanged)' manual.out) -eq 2 && grep -q '^ada,$item,15,' grades/manual.csv"
check "the gradebook counts them: ada 115/120, the item 15" \
  bash -c "test '$(cell grades/gradebook.csv 1 1)' = 115 && test '$(cell grades/gradebook.csv 1 17)' = 15"
check "results.json says them beside the autograder's score" python3 -c '
import json, sys
d = json.load(open("grades/students/ada/results.json"))
e = d["extra_data"]
sys.exit(not (d["score"] == 100 and e["total_with_manual"] == 115 and e["max_with_manual"] == 120 and
              e["manual_graded"][0]["score"] == 15 and e["manual_pending"] == []))'
check "the feedback pages show the points and the comment" \
  bash -c "grep -q '$item: 15/20 (the step, not the tolerance)' grades/students/ada/feedback.md &&
           grep -q '$item: 15/20' grades/students/ada/feedback.html"
check "bob's are still pending, and said" grep -q "$item: pending (20)" grades/students/bob/feedback.md
check "report.html counts them, and says who is pending" \
  bash -c "grep -q '1 student with items still pending' grades/report.html && grep -q '115/120' grades/report.html"

# Canvas: ada's grade with the manual points; bob's blank until his are given.
printf 'Student,ID,simlab id\nAda,1,ada\nBob,2,bob\n' >roster.csv
run_capture canvas "$SIMLAB" export canvas apple --grades grades --roster roster.csv -o canvas.csv --rubric rubric.toml
check "Canvas: out of 120, ada 115, bob blank while his item is pending (and said)" \
  bash -c "test '$(sed -n 2p canvas.csv)' = 'Points Possible,,,,,120' && test '$(cell canvas.csv 2 5)' = 115 &&
           test -z '$(cell canvas.csv 3 5)' && grep -q 'still pending' canvas.err"

# A test's points change: the recorded verdicts are re-scored, no code runs, the history says why.
sed -i '0,/^points = 10$/s//points = 30/' rubric.toml
"$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml >points.out 2>&1
check "a points-only change re-scores without running code: ada 135/140" \
  bash -c "test \$(grep -c '(unchanged)' points.out) -eq 2 && test '$(cell grades/gradebook.csv 1 1)' = 135 &&
           test '$(cell grades/gradebook.csv 1 2)' = 140"
check "and results.json has the new points" python3 -c '
import json, sys
d = json.load(open("grades/students/ada/results.json"))
sys.exit(not (d["score"] == 120 and max(t["max_score"] for t in d["tests"]) == 30))'
check "the history says why" \
  bash -c "test $(history_lines ada) -eq 2 && test \"$(last_why ada)\" = \"the rubric's points changed (re-scored from the recorded verdicts)\""

# A new submission is graded again, and the history keeps every grade.
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/bob/
"$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml >new.out 2>&1
check "bob's new file is graded and his history says why" \
  bash -c "test $(history_lines bob) -eq 3 && test '$(last_why bob)' = 'the submission changed'"

# A mistake in manual.csv: one line, exit 2, nothing changed.
cp grades/gradebook.csv gradebook.before
printf 'student,item,points,comment\nada,%s,25,\n' "$item" >grades/manual.csv
run_capture badsheet "$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml
check "25 points for an item worth 20: one line, exit 2, the gradebook as it was" \
  bash -c "test $(status_of badsheet) -eq 2 && test \$(wc -l <badsheet.err) -eq 1 && grep -q 'worth 0 to 20' badsheet.err &&
           cmp -s gradebook.before grades/gradebook.csv"
finish
