# The record from authority: who a student is comes from the platform's ids, never a name a student chose; when
# they handed in, from the platform's word (Canvas's LATE flag, Gradescope's created_at, the times the instructor
# names with --submitted), never a file's time alone; where the sources disagree the run says so and names the
# students. Each theft of an extension: a Gradescope name that is another's e-mail, a Canvas name that is another's
# ID, a Moodle file whose name holds another's number: the victim keeps their extension, the thief gets none. A
# copied Canvas download (every time the copy's): the disagreement said, nobody charged on the copy's times, the
# times given with --submitted charge as Canvas says. Bad input (an extensions file or times file with a student
# twice, an unknown one, a time that is not one) is one line naming the row, and the grades already there stay. A
# second run on a folder another holds stops before it takes anything in; a new object cache made by two at once.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
# gb GRADES ID COLUMN: a cell of the student's gradebook row, by the column's name
gb() { python3 -c '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/gradebook.csv")))
print(next(r[sys.argv[3]] for r in rows if r["student"] == sys.argv[2]))' "$@"; }
# late_says GRADES ID TEXT: the student's lateness line holds TEXT
late_says() { gb "$1" "$2" lateness | grep -q -- "$3"; }
export -f gb late_says
reference=$SOURCE_DIR/solutions/apple/NewtonsApple.cpp

# One course file: due 2026-10-03 06:59 UTC, 10 % a day, the extensions beside it.
mkdir course
cp "$SOURCE_DIR/assignments/apple/grading/rubric.toml" course/rubric.toml
printf '[late]\npenalty_percent = 10\nper = "day"\n\n[apple]\ndue = 2026-10-02T23:59:00-07:00\nextensions = "ext.csv"\n' \
  >course/course.toml
grade() {  # grade NAME DOWNLOAD PLATFORM [OPTIONS...]
  local name=$1 download=$2 platform=$3
  shift 3
  run_capture "$name" "$SIMLAB" grade apple "$download" -o "$name" --from "$platform" --rubric course/rubric.toml -j 2 "$@"
}

# Gradescope: Eve (SID 100) names herself Vic's e-mail; Vic (SID 70) has 3 days' extension, by his e-mail. Both
# handed in two days late.
mkdir -p gs/submission_1 gs/submission_2
cp "$reference" gs/submission_1/ && cp "$reference" gs/submission_2/
cat >gs/submission_metadata.yml <<'YML'
submission_1:
  :submitters:
  - :name: Vic Tim
    :sid: '70'
    :email: vic@example.edu
  :created_at: 2026-10-05 06:00:00.000000000 +00:00
submission_2:
  :submitters:
  - :name: vic@example.edu
    :sid: '100'
    :email: eve@example.edu
  :created_at: 2026-10-05 06:00:00.000000000 +00:00
YML
printf 'student,days\nvic@example.edu,3\n' >course/ext.csv
grade gs-grades gs gradescope
check "Gradescope: graded, one extension" bash -c "test $(status_of gs-grades) -eq 0 && grep -q ', 1 extension$' gs-grades.out"
check "  Vic keeps his extension: on time, 100" \
  bash -c "test '$(gb gs-grades 70 score)' = 100 && late_says gs-grades 70 'on time .extended to'"
check "  Eve, named as his e-mail, gets none: 2 days late, 80" \
  bash -c "test '$(gb gs-grades 100 score)' = 80 && ! late_says gs-grades 100 extended"

# Two submissions that give one SID (a SID a student typed): an extension by it is refused, naming both.
sed -i "s/:sid: '100'/:sid: '70'/" gs/submission_metadata.yml
printf 'student,days\n70,3\n' >course/ext.csv
grade gs-clash gs gradescope
check "Gradescope: an extension by a SID two students give is refused in one line naming both, nothing graded" \
  bash -c "test $(status_of gs-clash) -eq 2 && test \$(wc -l <gs-clash.err) -eq 1 &&
           grep -q \"row 2: '70' is an id of two students, 70 and 70-submission_2\" gs-clash.err &&
           ! test -e gs-clash/gradebook.csv"

# Canvas: Eve's display name is 103, Grace's Canvas ID; Grace has the extension, by her ID.
mkdir canvas
put() { cp "$reference" "canvas/$1" && touch -d "$2" "canvas/$1"; }
put hoppergrace_late_103_9001_NewtonsApple.cpp '2026-10-05 06:00:00 UTC'
put 103_late_104_9002_NewtonsApple.cpp '2026-10-05 06:00:00 UTC'
put lovelaceada_101_9003_NewtonsApple.cpp '2026-10-03 06:00:00 UTC'
printf 'student,days\n103,3\n' >course/ext.csv
grade canvas-grades canvas canvas
check "Canvas: Grace (ID 103) keeps her extension" \
  bash -c "test $(status_of canvas-grades) -eq 0 && test '$(gb canvas-grades hoppergrace_103 score)' = 100 &&
           late_says canvas-grades hoppergrace_103 'extended'"
check "  Eve, whose name is 103, gets none: late by Canvas's flag, 2 days, 80" \
  bash -c "test '$(gb canvas-grades 103_104 score)' = 80 && ! late_says canvas-grades 103_104 extended"

# Moodle, not in folders: Aaron's file is named so that a greedy reading gives Zed's number, 222.
mkdir moodle
cp "$reference" "moodle/Zed Victim_222_assignsubmission_file_NewtonsApple.cpp"
cp "$reference" "moodle/Aaron Evil_111_assignsubmission_file_Zed Victim_222_assignsubmission_file_NewtonsApple.cpp"
touch -d '2026-10-05 06:00:00 UTC' moodle/Zed*
touch -d '2026-10-05 07:00:00 UTC' moodle/Aaron*
printf 'student,days\n222,3\n' >course/ext.csv
grade moodle-grades moodle moodle
check "Moodle: Zed keeps his number and his extension" \
  bash -c "test $(status_of moodle-grades) -eq 0 && test '$(gb moodle-grades Zed-Victim_222 score)' = 100 &&
           late_says moodle-grades Zed-Victim_222 'extended'"
check "  Aaron's file is his: 111, no extension, late" \
  bash -c "grep -q '^Aaron Evil,,,,,Aaron-Evil_111,111,' moodle-grades/roster.csv &&
           ! late_says moodle-grades Aaron-Evil_111 extended &&
           test \$(grep -c '_222,' moodle-grades/roster.csv) -eq 1"

# A copied Canvas download: the copy's times are all one, after the due date. Canvas flagged two late.
mkdir copied
cp -r canvas/. copied/ && rm copied/103_late_104_9002_NewtonsApple.cpp
cp "$reference" copied/turing_late_104_9004_NewtonsApple.cpp
touch -d '2026-11-20 12:00:00 UTC' copied/*
printf 'student,days\n' >course/ext.csv
grade copied-grades copied canvas
check "a copied download: the run says every time is the copy's, and names those Canvas flags late" \
  bash -c "test $(status_of copied-grades) -eq 0 &&
           grep -q '^Hand-in times: every student.s time is the same, 2026-11-20T12:00:00Z: .*Canvas flags 2 students late, not charged until --submitted gives their times: hoppergrace_103, turing_104$' copied-grades.out &&
           grep -q 'Hand-in times: every student.* time is the same' copied-grades/report.html"
check "  nobody is charged on the copy's times: on time by Canvas's flag, 100" \
  bash -c "test '$(gb copied-grades lovelaceada_101 score)' = 100 &&
           late_says copied-grades lovelaceada_101 'on time by Canvas.s flag'"
check "  those Canvas flags late are not charged until a time says how late" \
  bash -c "test '$(gb copied-grades turing_104 score)' = 100 &&
           late_says copied-grades turing_104 'late by Canvas.s flag, but no time known'"
# Canvas's times, from its API, named with --submitted: they say how late, the flags say who.
cat >times.json <<'JSON'
[{"user_id": 101, "submitted_at": "2026-10-03T09:00:00Z", "late": false},
 {"user_id": 103, "submitted_at": "2026-10-04T06:00:00Z", "late": true},
 {"user_id": 104, "submitted_at": "2026-10-05T06:00:00Z", "late": true}]
JSON
grade copied-grades copied canvas --submitted times.json
check "--submitted: Canvas's times charge those it flags late (1 day: 90, 2 days: 80), nothing else changes" \
  bash -c "test $(status_of copied-grades) -eq 0 && test '$(gb copied-grades hoppergrace_103 score)' = 90 &&
           test '$(gb copied-grades turing_104 score)' = 80 && test '$(gb copied-grades lovelaceada_101 score)' = 100 &&
           grep -q '^0 graded, 3 up to date' copied-grades.out"
check "  Ada, on time by Canvas's flag but past the due date by its time: the disagreement said, naming her" \
  grep -q '^Hand-in times: Canvas.s late flag and the time disagree for 1 student (.*): lovelaceada_101; ' copied-grades.out
check "  and on time all the same, the time it did not use given" \
  grep -q 'on time by Canvas.s flag (--submitted times.json, 2026-10-03T09:00:00Z, is later: not used)' \
  copied-grades/gradebook.csv

# Bad input: one line naming the row; the grades already there stay as they were.
cp copied-grades/gradebook.csv before.csv
bad() {  # bad NAME EXTENSIONS-CSV TIMES-CSV WHAT
  printf '%b' "$2" >course/ext.csv
  printf '%b' "$3" >times.csv
  grade copied-grades copied canvas --submitted times.csv
  mv copied-grades.err "bad-$1.err"
  check "bad input ($1): one line naming the row, exit 2, the gradebook as it was" refused "$1" "$4"
}
refused() {  # refused NAME WHAT: exit 2, one line saying WHAT, the gradebook as it was
  test "$(status_of copied-grades)" -eq 2 && test "$(wc -l <"bad-$1.err")" -eq 1 && grep -qF -- "$2" "bad-$1.err" &&
    cmp -s before.csv copied-grades/gradebook.csv
}
times='student,submitted\n101,2026-10-03T09:00:00Z\n'
bad ext-twice 'student,days\n103,1\nhoppergrace_103,2\n' "$times" 'ext.csv, row 3: hoppergrace_103 has row 2 too'
bad ext-unknown 'student,days\n999,1\n' "$times" "ext.csv, row 2: '999' is no student of the class"
bad ext-time 'student,due\n103,Friday\n' "$times" "ext.csv, row 2: due 'Friday' is not a date-time"
bad times-twice 'student,days\n' 'student,submitted\n101,2026-10-03T09:00:00Z\nlovelaceada_101,2026-10-03T09:00:00Z\n' \
  'times.csv, row 3: lovelaceada_101 has row 2 too'
bad times-unknown 'student,days\n' 'student,submitted\nnobody,2026-10-03T09:00:00Z\n' "times.csv, row 2: 'nobody' is no student"
bad times-time 'student,days\n' 'student,submitted\n101,yesterday\n' "times.csv, row 2: 'yesterday' is not a date-time"

# A roster.csv whose time is not one (an edit), read by a class taken in earlier; a Canvas roster that gives one ID
# to two rows: one line naming the row, nothing changed.
cp canvas-grades/gradebook.csv canvas-before.csv
python3 - canvas-grades/roster.csv <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
rows[1][rows[0].index("Submitted")] = "garbage"
csv.writer(open(sys.argv[1], "w", newline="")).writerows(rows)
PY
run_capture roster-time "$SIMLAB" grade apple canvas-grades/class -o canvas-grades --rubric course/rubric.toml
check "a roster.csv time that is not one: one line naming the row, the gradebook as it was" \
  bash -c "test $(status_of roster-time) -eq 2 && test \$(wc -l <roster-time.err) -eq 1 &&
           grep -q 'roster.csv, row 2: Submitted .garbage. is not a date-time' roster-time.err &&
           cmp -s canvas-before.csv canvas-grades/gradebook.csv"
printf 'Student,ID,SIS User ID,SIS Login ID,Section\n"Hopper, Grace",103,,,A\n"Someone, Else",103,,,A\n' >twice.csv
run_capture export-twice "$SIMLAB" export canvas apple --grades canvas-grades --roster twice.csv -o upload.csv
check "a Canvas roster that gives one ID to two rows: one line naming the row, nothing written" \
  bash -c "test $(status_of export-twice) -eq 2 && test \$(wc -l <export-twice.err) -eq 1 &&
           grep -q 'twice.csv, row 3: ID 103 is row 2.s too' export-twice.err && ! test -e upload.csv"

# A plain class folder, copied: its files' times are all the copy's. Said, and nobody is charged on them.
mkdir -p plain/ada plain/bob && cp "$reference" plain/ada/ && cp "$reference" plain/bob/
touch -d '2026-11-20 12:00:00 UTC' plain/*/NewtonsApple.cpp
run_capture plain "$SIMLAB" grade apple plain -o plain-grades --rubric course/rubric.toml -j 2
check "a copied class folder: every time the same, said; nobody charged on it" \
  bash -c "test $(status_of plain) -eq 0 && grep -q '^Hand-in times: every student.s time is the same, 2026-11-20T12:00:00Z' plain.out &&
           test '$(gb plain-grades ada score)/$(gb plain-grades bob score)' = 100/100"

# Another simlab holds the folder: the second stops at its lock before it takes the download in.
mkdir held
exec 8>held/.simlab-lock && flock -n 8
grade held canvas canvas
exec 8>&-
check "a second run stops at the lock before it writes: no class taken in, no roster" \
  bash -c "test $(status_of held) -eq 2 && grep -q 'another simlab is writing into held' held.err &&
           test \"\$(ls -A held)\" = .simlab-lock"

# A new object cache, three folders deep, made by two simlabs at once: both grade.
cp "$reference" NewtonsApple.cpp
for n in 1 2; do SIMLAB_CACHE=$work/fresh/cache/objects "$SIMLAB" check apple NewtonsApple.cpp >"cache-$n.out" 2>&1 & done
wait
check "a new object cache made by two simlabs at once: both grade" \
  bash -c "grep -q '^Score: ' cache-1.out && grep -q '^Score: ' cache-2.out"
finish
