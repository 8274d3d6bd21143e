# A course's late policy (course.toml) on a Canvas download, then the grades back to Canvas: the due date, a
# penalty per day with a grace day and a cap, a cutoff, two extensions (one by Canvas's ID, one by a new due date),
# each student timed by the download's own file times; the gradebook shows the raw score, the penalty and the
# final; Canvas's own gradebook export is matched by its ID column (the folder names are simlab's), a roster that
# matches nobody is refused in one line, and the feedback is zipped under Canvas's names for its re-upload.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
# gb GRADES ID COLUMN: a cell of the student's gradebook row, by the column's name
gb() { python3 -c '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/gradebook.csv")))
print(next(r[sys.argv[3]] for r in rows if r["student"] == sys.argv[2]))' "$@"; }
cell() { python3 -c 'import csv,sys; print(list(csv.reader(open(sys.argv[1])))[int(sys.argv[2])][int(sys.argv[3])])' "$@"; }
reference=$SOURCE_DIR/solutions/apple/NewtonsApple.cpp

# Due 2026-10-02 23:59 at UTC-7, that is 2026-10-03 06:59 UTC. Canvas's zip keeps each file's submission time.
mkdir canvas
put() { cp "$reference" "canvas/$1" && touch -d "$2" "canvas/$1"; }
put lovelaceada_101_9001_NewtonsApple.cpp '2026-10-03 06:00:00 UTC'          # on time
put babbagecharles_late_102_9002_NewtonsApple.cpp '2026-10-04 08:59:00 UTC'  # 26 h late: 1 grace day, 1 day charged
put hopper_late_103_9003_NewtonsApple.cpp '2026-10-06 06:00:00 UTC'          # 47 h late, but 3 days' extension
put turing_late_104_9004_NewtonsApple.cpp '2026-10-06 07:59:00 UTC'          # 1 h past their own due date
put noether_late_105_9005_NewtonsApple.cpp '2026-10-20 00:00:00 UTC'         # after the cutoff
put knuth_late_106_9006_NewtonsApple.cpp '2026-10-12 06:59:00 UTC'           # 9 days late: the cap

mkdir course
cp "$SOURCE_DIR/assignments/apple/grading/rubric.toml" course/rubric.toml
cat >course/course.toml <<'EOF'
[late]
penalty_percent = 10
per = "day"
max_percent = 50
grace_days = 1

[apple]
due = 2026-10-02T23:59:00-07:00
cutoff = 2026-10-16T23:59:00-07:00
extensions = "apple-extensions.csv"
EOF
cat >course/apple-extensions.csv <<'EOF'
student,due,days
103,,3
turing_104,2026-10-05T23:59:00-07:00,
EOF

run_capture graded "$SIMLAB" grade apple canvas -o grades --from canvas --rubric course/rubric.toml -j 2
check "graded, the policy found beside the rubric and said in one line" \
  bash -c "test $(status_of graded) -eq 0 && grep -q 'Late policy of course/course.toml: due 2026-10-03T06:59:00Z, 10 % per day (at most 50 %), 1 grace day(s), no credit after 2026-10-17T06:59:00Z, 2 extensions' graded.out"
check "the roster keeps each submission's time, from Canvas's file times" \
  grep -q '^babbagecharles,102,,,,babbagecharles_102,,,late,2026-10-04T08:59:00Z,Canvas.s file time,,,babbagecharles_late_102_9002$' grades/roster.csv
check "the gradebook has the raw score, the penalty and the final" \
  test "$(head -1 grades/gradebook.csv | cut -d, -f1-8)" = "student,score,max,status,raw score,late penalty,submitted,lateness"
check "on time: 100, nothing taken" \
  test "$(gb grades lovelaceada_101 score)/$(gb grades lovelaceada_101 'late penalty')" = "100/0"
check "26 h late with a grace day: one day charged, 10 % (90)" \
  test "$(gb grades babbagecharles_102 score)/$(gb grades babbagecharles_102 'raw score')/$(gb grades babbagecharles_102 'late penalty')" = "90/100/10"
check "an extension of 3 days by Canvas's ID: on time" \
  bash -c "test '$(gb grades hopper_103 score)' = 100 && grep -q 'on time (extended to 2026-10-06T06:59:00Z)' <<<'$(gb grades hopper_103 lateness)'"
check "an extension to a new due date, 1 h past it, within the grace day: nothing taken" \
  bash -c "test '$(gb grades turing_104 score)' = 100 &&
           grep -q 'handed in 1 h late (extended to 2026-10-06T06:59:00Z), within the 1 grace day: no penalty' <<<'$(gb grades turing_104 lateness)'"
check "after the cutoff: no credit" \
  bash -c "test '$(gb grades noether_105 score)' = 0 && grep -q 'after the cutoff' <<<'$(gb grades noether_105 lateness)'"
check "9 days late: the cap of 50 %" test "$(gb grades knuth_106 score)" = 50
check "report.html counts those who lost points" grep -q "Late work (course.toml): 3 students lost points to it" grades/report.html
check "the student's feedback says it, with the points taken" \
  grep -q 'Lateness: handed in 26 h late, 1 grace day: 10 % of the score taken (10 % per day): 10 points off the 100 earned' \
  grades/students/babbagecharles_102/feedback.md
check "results.json's score carries the penalty for Gradescope's gradebook too" \
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(not (d["score"] == 50 and d["extra_data"]["late"]["percent"] == 50))' \
  grades/students/knuth_106/results.json

# A policy changed: nothing is graded again, the penalties are made again.
sed -i 's/penalty_percent = 10/penalty_percent = 20/' course/course.toml
run_capture again "$SIMLAB" grade apple canvas -o grades --from canvas --rubric course/rubric.toml -j 2
check "a changed policy regrades nothing and applies at once" \
  bash -c "grep -q '^0 graded, 6 up to date' again.out && test '$(gb grades babbagecharles_102 score)' = 80"

# Taken in alone (as a cluster run needs), then graded as a class folder: the roster's times give the same penalties.
run_capture intake "$SIMLAB" grade apple canvas -o split --from canvas --intake-only
run_capture split "$SIMLAB" grade apple split/class -o split --rubric course/rubric.toml -j 2
check "--intake-only grades nothing; the class graded after it has the download's times and penalties" \
  bash -c "test $(status_of intake) -eq 0 && grep -q 'Nothing graded (--intake-only)' intake.out &&
           test $(status_of split) -eq 0 && test '$(gb split babbagecharles_102 score)' = 80 &&
           test '$(gb split babbagecharles_102 submitted)' = 2026-10-04T08:59:00Z"

# Canvas's own gradebook export: its ID column, no simlab id; Canvas adds a Points Possible row.
cat >canvas-gradebook.csv <<'EOF'
Student,ID,SIS User ID,SIS Login ID,Section,Newton's apple (777)
    Points Possible,,,,,100
"Lovelace, Ada",101,s1,alovelace,Lab A,
"Babbage, Charles",102,s2,cbabbage,Lab A,
"Knuth, Donald",106,s6,dknuth,Lab B,
"Nobody, Ned",199,s9,nned,Lab B,
EOF
run_capture export "$SIMLAB" export canvas apple --grades grades --roster canvas-gradebook.csv -o upload.csv \
  --canvas-id 777 --comments comments.zip
check "Canvas's own export matched by its ID column" \
  bash -c "test $(status_of export) -eq 0 && grep -q '3 of 4 students on the roster scored (out of 100), 3 matched by Canvas.s ID or SIS User ID' export.out"
check "the final scores go back, the penalty taken" \
  test "$(cell upload.csv 2 5),$(cell upload.csv 3 5),$(cell upload.csv 4 5),$(cell upload.csv 5 5)" = "100,80,50,"
check "the comments zip holds each feedback page under Canvas's name for its submission" \
  bash -c "unzip -l comments.zip | grep -q ' babbagecharles_late_102_9002_simlab-feedback.html$' &&
           test \$(unzip -Z1 comments.zip | wc -l) -eq 3"
cat >other-course.csv <<'EOF'
Student,ID,SIS User ID,SIS Login ID,Section
"Someone, Else",901,x1,selse,Lab A
EOF
run_capture nomatch "$SIMLAB" export canvas apple --grades grades --roster other-course.csv -o nomatch.csv
check "a roster that matches nobody graded is refused in one line, nothing written" \
  bash -c "test $(status_of nomatch) -eq 2 && test \$(wc -l <nomatch.err) -eq 1 &&
           grep -q 'no student of other-course.csv matches one of the 6 graded' nomatch.err && ! test -e nomatch.csv"

# Gradescope's autograder: created_at against course.toml's rules, the due date from the metadata (the student's
# own, an extension given in Gradescope, before the assignment's).
mkdir -p gs/submission gs/results
cp "$reference" gs/submission/
printf '[late]\npenalty_percent = 10\nper = "day"\n' >rules.toml
meta() {  # meta OWN_DUE: the metadata, handed in 26 h after the assignment's due date
  printf '{"created_at": "2026-10-04T01:59:00.365935-07:00", "assignment": {"due_date": "2026-10-02T23:59:00.000000-07:00", "late_due_date": null}, "users": [{"sid": "s7", "email": "g@x.edu", "assignment": {"due_date": "%s"}}]}' "$1" \
    >gs/submission_metadata.json
}
meta "2026-10-02T23:59:00.000000-07:00"
run_capture auto "$SIMLAB" autograde apple --submission gs/submission --results gs/results/results.json --course rules.toml
check "autograde: 26 h past Gradescope's due date, two days at 10 %: 80, and it says so" \
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(not (d["score"] == 80 and d["extra_data"]["late"]["percent"] == 20 and "Lateness: handed in 26 h late" in d["output"]))' \
  gs/results/results.json
meta "2026-10-04T23:59:00.000000-07:00"
run_capture auto-extended "$SIMLAB" autograde apple --submission gs/submission --results gs/results/results.json --course rules.toml
check "autograde: the student's own due date in the metadata (an extension) puts it on time" \
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(not (d["score"] == 100 and d["extra_data"]["late"]["percent"] == 0))' \
  gs/results/results.json

# Bad policies: one line, nothing graded.
bad() {  # bad NAME TOML WHAT
  mkdir -p "bad-$1" && printf '%b' "$2" >"bad-$1/course.toml"
  run_capture "bad-$1" "$SIMLAB" grade apple canvas -o "bad-$1/grades" --from canvas --course "bad-$1/course.toml"
  check "bad course.toml ($1): one line, exit 2" \
    bash -c "test $(status_of "bad-$1") -eq 2 && test \$(wc -l <bad-$1.err) -eq 1 && grep -q '$3' bad-$1.err"
}
bad no-offset '[apple]\ndue = 2026-10-02T23:59:00\n' 'has no offset'
bad not-a-date '[apple]\ndue = "Friday"\n' 'is not a date-time'
bad percent '[late]\npenalty_percent = 150\n[apple]\ndue = 2026-10-02T23:59:00Z\n' 'penalty_percent must be a number from 0 to 100'
bad per '[late]\nper = "week"\n[apple]\ndue = 2026-10-02T23:59:00Z\n' 'per must be "day" or "hour"'
bad no-file '[apple]\ndue = 2026-10-02T23:59:00Z\nextensions = "none.csv"\n' 'no extensions'
finish
