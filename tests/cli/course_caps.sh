# What a course keeps around a grade (course.toml): a cap on graded submissions, read on Gradescope from its own
# submission_metadata.json (previous_submissions, each with its submission_time, score and results); a bank of slip
# days spent across the labs graded side by side under one grades folder, in the order of their due dates. Bad
# rules and a metadata file that cannot be checked: one line each, nothing graded lost.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
# gb GRADES ID COLUMN: a cell of the student's gradebook row, by the column's name
gb() { python3 -c '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/gradebook.csv")))
print(next(r[sys.argv[3]] for r in rows if r["student"] == sys.argv[2]))' "$@"; }
# results FILE PYTHON-EXPRESSION: true when the expression holds of results.json (d)
results() { python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); sys.exit(not eval("(" + sys.argv[2] + ")"))' "$@"; }

# --- A cap of three on Gradescope --------------------------------------------------------------------------------------
mkdir -p gs/submission gs/results
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" gs/submission/
printf '[apple]\nmax_submissions = 3\n' >capped.toml
# meta CREATED_AT PREVIOUS: Gradescope's metadata as its documentation gives it, PREVIOUS the previous_submissions
# list (or "none": the key left out).
meta() {
  python3 - "$1" "$2" >gs/submission_metadata.json <<'PY'
import json, sys
created, previous = sys.argv[1], sys.argv[2]
earlier = lambda t, score, first: {
    "submission_time": t, "score": score,
    "results": {"score": float(score), "output": "", "stdout_visibility": "hidden",
                "tests": [{"name": "the apple falls", "score": float(score), "max_score": 100.0, "status": "passed" if first else "failed"}],
                "extra_data": {}}}
metadata = {
    "id": 123456, "created_at": created,
    "assignment": {"due_date": "2026-10-31T23:00:00.000000-07:00", "group_size": None, "group_submission": False,
                   "id": 25828, "course_id": 1234, "late_due_date": None,
                   "release_date": "2026-09-20T00:00:00.000000-07:00", "title": "Newton's apple",
                   "total_points": "100.0"},
    "submission_method": "upload",
    "users": [{"email": "ada@example.edu", "id": 1234, "name": "Ada Lovelace", "sid": "s101"}]}
if previous != "none":
    three = [earlier("2026-10-01T09:00:00.000000-07:00", 40.0, True),
             earlier("2026-10-01T10:00:00.000000-07:00", "85.0", True),   # Gradescope gives some scores as text
             earlier("2026-10-01T11:00:00.000000-07:00", 70.0, True)]
    metadata["previous_submissions"] = three[:int(previous)]
json.dump(metadata, sys.stdout, indent=2)
PY
}
autograde() {  # autograde NAME COURSE-FILE
  rm -f gs/results/results.json
  run_capture "$1" "$SIMLAB" autograde apple --submission gs/submission --results gs/results/results.json --course "$2"
}

meta "2026-10-02T09:00:00.000000-07:00" 3
autograde fourth capped.toml
check "a fourth submission past a cap of three is not graded: the last counted score (70, not the best 85) stays" \
  bash -c "test $(status_of fourth) -eq 0 &&
           grep -qx 'Submissions: not graded: past the 3 graded submissions the course counts; your score stays 70, from your submission of 2026-10-01T18:00:00Z' fourth.out &&
           ! grep -q 'Score:' fourth.out"
check "its results.json: the score and tests of the one it keeps, the line first in its output, and the standing" \
  results gs/results/results.json 'd["score"] == 70 and d["tests"][0]["score"] == 70 and
    d["output"].startswith("Submissions: not graded: past the 3") and d["output"].count("\n") == 1 and
    d["extra_data"]["submissions"] == {"checked": True, "max": 3, "counted": False, "number": 3, "left": 0}'

meta "2026-10-01T12:00:00.000000-07:00" 2
autograde third capped.toml
check "the third is graded and counted, with none left said" \
  bash -c "test $(status_of third) -eq 0 &&
           grep -qx 'Submissions: graded submission 3 of the 3 graded submissions the course counts: none left' third.out"
check "its results.json: the score it earned, and the standing" \
  results gs/results/results.json 'd["score"] == 100 and d["output"].startswith("Submissions: graded submission 3 of the 3") and
    d["extra_data"]["submissions"] == {"checked": True, "max": 3, "counted": True, "number": 3, "left": 0}'

# A metadata file without previous_submissions: nothing to count against, so graded, counted, and said in one line.
meta "2026-10-02T09:00:00.000000-07:00" none
autograde unchecked capped.toml
check "metadata without previous_submissions: graded and counted, said in one line" \
  bash -c "test $(status_of unchecked) -eq 0 &&
           test \$(grep -c '^Submissions:' unchecked.out) -eq 1 &&
           grep -qx 'Submissions: the course counts 3 graded submissions, but this one cannot be checked against them: submission_metadata.json has no previous_submissions; graded, and counted' unchecked.out"
check "its results.json: the score it earned, unchecked" \
  results gs/results/results.json 'd["score"] == 100 and d["extra_data"]["submissions"] == {"checked": False, "max": 3}'

# A negative cap: one line, and results.json says the autograder could not grade it, which no cap counts.
printf '[apple]\nmax_submissions = -1\n' >negative.toml
autograde negative-auto negative.toml
check "autograde: a negative cap is refused in one line naming the file, exit 2" \
  bash -c "test $(status_of negative-auto) -eq 2 && test \$(wc -l <negative-auto.err) -eq 1 &&
           grep -q 'negative.toml \[apple\]: max_submissions must be a whole number from 1 to 1000' negative-auto.err" &&
  results gs/results/results.json 'd["score"] == 0 and d["extra_data"] == {"graded": False}'  # a cap does not count it

# simlab check cannot know how many are left: it says the cap, and that a self-check is none of them.
mkdir check && cp "$SOURCE_DIR/assignments/apple/grading/rubric.toml" check/ &&
  printf '[apple]\nmax_submissions = 3\nsubmission_window_hours = 24\n' >check/course.toml
run_capture self-check "$SIMLAB" check apple gs/submission/NewtonsApple.cpp --rubric check/rubric.toml
check "simlab check says the cap beside the rubric, and that a check is none of the counted submissions" \
  grep -qx 'Graded submissions: the course counts 3 each 24 h on its platform; this check is none of them, and the platform.s results say how many you have left' self-check.out

# --- A bank of 3 slip days across the apple and the projectile ---------------------------------------------------------
# ada is 2 days late on the apple (47 h) and 2 on the projectile (36 h): the bank covers the apple's and one of the
# projectile's, 10 % off it. bob is on time on the apple: the bank covers his 2 days on the projectile.
for s in ada bob; do
  mkdir -p "classes/apple/$s" "classes/projectile/$s"
  cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" "classes/apple/$s/"
  cp "$SOURCE_DIR/solutions/projectile/ProjectileMotion.cpp" "classes/projectile/$s/"
done
cat >course.toml <<'EOF'
[late]
penalty_percent = 10
per = "day"
slip_days = 3

[apple]
due = 2026-10-02T23:59:00-07:00

[projectile]
due = 2026-10-09T23:59:00-07:00
EOF
printf 'student,submitted\nada,2026-10-05T05:59:00Z\nbob,2026-10-03T06:00:00Z\n' >apple-times.csv
printf 'student,submitted\nada,2026-10-11T18:59:00Z\nbob,2026-10-11T18:59:00Z\n' >projectile-times.csv
grade() {  # grade NAME LAB TIMES [COURSE-FILE]: the lab's class into grades/LAB
  run_capture "$1" "$SIMLAB" grade "$2" "classes/$2" -o "grades/$2" --course "${4:-course.toml}" --submitted "$3" -j 2
}

grade apple apple apple-times.csv
check "the apple: 2 days late, both from the bank: nothing taken, 1 left" \
  bash -c "test $(status_of apple) -eq 0 && test '$(gb grades/apple ada score)/$(gb grades/apple ada 'late penalty')' = 100/0 &&
           test '$(gb grades/apple ada 'slip days used')/$(gb grades/apple ada 'slip days left')' = 2/1 &&
           test '$(gb grades/apple ada lateness)' = 'handed in 47 h late, 2 slip days spent: no penalty'"
check "the run says the bank and where it is kept" \
  grep -qx 'Slip days: 3 for each student, spent in the order of the labs. due dates across grades (before apple: no lab graded)' apple.out

grade projectile projectile projectile-times.csv
check "the projectile: 2 days late, 1 left in the bank: 10 % off" \
  bash -c "test $(status_of projectile) -eq 0 &&
           test '$(gb grades/projectile ada 'raw score')/$(gb grades/projectile ada score)/$(gb grades/projectile ada 'late penalty')' = 100/90/10 &&
           test '$(gb grades/projectile ada 'slip days used')/$(gb grades/projectile ada 'slip days left')' = 1/0"
check "bob, on time on the apple, has the whole bank for the projectile's 2 days: nothing taken" \
  test "$(gb grades/projectile bob score)/$(gb grades/projectile bob 'slip days used')/$(gb grades/projectile bob 'slip days left')" = 100/2/1
check "the ledger in the gradebook, the feedback, results.json and the report" \
  bash -c "test '$(gb grades/projectile ada 'slip days')' = '2 on apple, 1 on projectile (this lab); 0 of 3 left' &&
           grep -qx 'Slip days: 2 on apple, 1 on projectile (this lab); 0 of 3 left.' grades/projectile/students/ada/feedback.md &&
           grep -q 'Slip days: 2 on apple, 1 on projectile (this lab); 0 of 3 left' grades/projectile/students/ada/feedback.html &&
           grep -q '2 students spent 3 days on this lab; 1 student has none left after it' grades/projectile/report.html" &&
  results grades/projectile/students/ada/results.json \
    'd["score"] == 90 and d["extra_data"]["late"]["slip_days"] == {"used": 1, "left": 0, "bank": 3}'

# Canvas's gradebook gets the score after the penalty, and the export says who spent days.
printf 'Student,ID,SIS User ID,SIS Login ID,Section,simlab id\n"Lovelace, Ada",101,s1,ada,A,ada\n"B, Bob",102,s2,bob,A,bob\n' \
  >canvas-roster.csv
run_capture export "$SIMLAB" export canvas projectile --grades grades/projectile --roster canvas-roster.csv -o upload.csv
check "the Canvas export: 90 and 100, and the students who spent slip days counted" \
  bash -c "test $(status_of export) -eq 0 && grep -q '^2 spent slip days on this lab (gradebook.csv and each one.s feedback give the ledger' export.out &&
           python3 -c 'import csv; r = list(csv.reader(open(\"upload.csv\"))); print(r[2][-1], r[3][-1])' | grep -qx '90 100'"

# The apple graded again with ada on time: no code runs, and the run names the lab whose days it moved; the
# projectile graded again (no code runs either) gives ada the whole bank.
printf 'student,submitted\nada,2026-10-03T06:00:00Z\nbob,2026-10-03T06:00:00Z\n' >apple-times.csv
grade apple-again apple apple-times.csv
check "regrading the apple names the projectile, whose slip days it moved" \
  bash -c "test $(status_of apple-again) -eq 0 && grep -q '^0 graded, 2 up to date' apple-again.out &&
           grep -q '^Slip days: the slip days spent on projectile (1 student: ada) are not what the bank now gives them' apple-again.out"
grade projectile-again projectile projectile-times.csv
check "the projectile graded again: ada's 2 days from the bank, nothing taken, and nothing left stale" \
  bash -c "test $(status_of projectile-again) -eq 0 && grep -q '^0 graded, 2 up to date' projectile-again.out &&
           test '$(gb grades/projectile ada score)/$(gb grades/projectile ada 'slip days')' = '100/2 on projectile (this lab); 1 of 3 left' &&
           ! grep -q 'are not what the bank now gives them' projectile-again.out"

# Bad rules on a class already graded: one line, exit 2, the grades as they were.
# What the grades hold (their lock aside, which each run takes): the same before and after a refused run.
sums() { find grades -type f ! -name .simlab-lock -exec md5sum {} + | sort; }
export -f sums
sums >before.sums
bad() {  # bad NAME TOML WHAT
  printf '%b' "$2" >"$1.toml"
  grade "$1" projectile projectile-times.csv "$1.toml"
  check "bad course.toml ($1): one line, exit 2, nothing graded lost" \
    bash -c "test $(status_of "$1") -eq 2 && test \$(wc -l <$1.err) -eq 1 && grep -qF -- '$3' $1.err &&
             cmp -s <(sums) before.sums"
}
bad negative-cap '[projectile]\ndue = 2026-10-09T23:59:00-07:00\nmax_submissions = -1\n' \
  'negative-cap.toml [projectile]: max_submissions must be a whole number from 1 to 1000'
bad no-due-dates '[late]\npenalty_percent = 10\nslip_days = 3\n[apple]\nmax_submissions = 3\n[projectile]\nmax_submissions = 3\n' \
  'no-due-dates.toml [late]: slip_days = 3, but no assignment has a due date'
run_capture elsewhere "$SIMLAB" grade projectile classes/projectile -o grades/elsewhere --course course.toml \
  --submitted projectile-times.csv
check "a bank of slip days needs each lab graded into a folder named after it: one line, exit 2" \
  bash -c "test $(status_of elsewhere) -eq 2 && test \$(wc -l <elsewhere.err) -eq 1 &&
           grep -q 'grade into a folder named projectile, not grades/elsewhere' elsewhere.err && ! test -e grades/elsewhere"
finish
