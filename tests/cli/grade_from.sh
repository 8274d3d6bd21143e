# simlab grade --from: each platform's download graded as it comes, laid out as the platform's documentation and
# its users' parsers describe it - Canvas's flat files (late ones, resubmissions), Gradescope's export (its
# submission_metadata.yml, a group), Moodle's folders (an online text beside the file), GitHub Classroom's
# repositories (the file deep inside) - one row per student or group, with names and flags in roster.csv; the same
# folders without --from, and a folder of loose files, are refused in one line naming what to do.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
cell() { python3 -c 'import csv,sys; print(list(csv.reader(open(sys.argv[1])))[int(sys.argv[2])][int(sys.argv[3])])' "$@"; }
rows() { python3 -c 'import csv,sys; print(len(list(csv.reader(open(sys.argv[1])))) - 1)' "$1"; }
# score_of GRADES ID: the student's score in the gradebook
score_of() { python3 -c '
import csv, sys
for row in csv.reader(open(sys.argv[1] + "/gradebook.csv")):
    if row[0] == sys.argv[2]: print(row[1] + " " + row[3])' "$1" "$2"; }
reference=$SOURCE_DIR/solutions/apple/NewtonsApple.cpp
starter=$SOURCE_DIR/starter/apple/NewtonsApple.cpp

# Canvas: name_userid_submissionid_file; "late" after the name; "-1" before the extension for a resubmission.
mkdir canvas
cp "$reference" canvas/lovelaceada_101_9001_NewtonsApple.cpp
cp "$starter" canvas/babbagecharles_late_102_9002_NewtonsApple.cpp
cp "$reference" canvas/babbagecharles_late_102_9003_NewtonsApple-1.cpp
echo "my notes" >canvas/hoppergrace_103_9004_notes.txt
run_capture canvas-refused "$SIMLAB" grade apple canvas -o canvas-grades
check "Canvas's download without --from: refused in one line naming --from canvas" \
  bash -c "test $(status_of canvas-refused) -eq 2 && grep -q 'looks like a canvas download: add --from canvas' canvas-refused.err &&
           test \$(wc -l <canvas-refused.err) -eq 1 && ! test -e canvas-grades/gradebook.csv"
run_capture canvas-graded "$SIMLAB" grade apple canvas -o canvas-grades --from canvas -j 2
check "Canvas: one row per student, ids from the name and Canvas's user id" \
  bash -c "test $(status_of canvas-graded) -eq 0 && test $(rows canvas-grades/gradebook.csv) -eq 3"
check "the latest resubmission is graded (the reference, 100)" test "$(score_of canvas-grades babbagecharles_102)" = "100 graded"
check "and the first student's file (100)" test "$(score_of canvas-grades lovelaceada_101)" = "100 graded"
check "a student who handed in no C++ file is a missing file, not a silent row" \
  test "$(score_of canvas-grades hoppergrace_103)" = "0 missing file"
check "the roster has Canvas's ID and the late flag" \
  bash -c "grep -q '^babbagecharles,102,,,,babbagecharles_102,,,late,' canvas-grades/roster.csv &&
           grep -q '^lovelaceada,101,,,,lovelaceada_101,,,,' canvas-grades/roster.csv"
check "and Canvas's name for the latest submission, which a comment re-uploaded to it must carry" \
  grep -q '^babbagecharles,.*,babbagecharles_late_102_9003$' canvas-grades/roster.csv

# Gradescope: submission_metadata.yml beside submission_<id>/ folders; a group of two.
mkdir -p gradescope/submission_901 gradescope/submission_902
cp "$reference" gradescope/submission_901/
cp "$starter" gradescope/submission_902/
cat >gradescope/submission_metadata.yml <<'YML'
---
submission_901:
  :submitters:
  - :name: Ada Lovelace
    :sid: '101'
    :email: ada@example.edu
  :created_at: 2026-11-20 10:00:00.000000000 +00:00
  :score: 0.0
  :status: processed
submission_902:
  :submitters:
  - :name: Fay Team
    :sid: '201'
    :email: fay@example.edu
  - :name: Gus Team
    :sid: '202'
    :email: gus@example.edu
  :created_at: 2026-11-21 10:00:00.000000000 +00:00
YML
run_capture gs-refused "$SIMLAB" grade apple gradescope -o gs-grades
check "Gradescope's export without --from: refused, naming --from gradescope" \
  grep -q 'looks like a gradescope download: add --from gradescope' gs-refused.err
run_capture gs-graded "$SIMLAB" grade apple gradescope -o gs-grades --from gradescope -j 2
check "Gradescope: a row per submission, ids from the SIDs, a group's joined" \
  bash -c "test $(status_of gs-graded) -eq 0 && test $(rows gs-grades/gradebook.csv) -eq 2 &&
           test '$(score_of gs-grades 101)' = '100 graded' && test '$(score_of gs-grades 201+202)' = '0 graded'"
check "the roster names each member, with e-mail, Gradescope's created_at and group" \
  bash -c "test $(rows gs-grades/roster.csv) -eq 3 &&
           grep -q '^Gus Team,,202,,,201+202,,gus@example.edu,,2026-11-21T10:00:00Z,Gradescope.s created_at,\"Fay Team, Gus Team\",' gs-grades/roster.csv"
run_capture gs-canvas "$SIMLAB" export canvas apple --grades gs-grades --roster gs-grades/roster.csv -o gs-canvas.csv
check "exported to Canvas with that roster, each member gets the group's grade" \
  bash -c "test $(status_of gs-canvas) -eq 0 && test '$(cell gs-canvas.csv 2 5)' = 100 &&
           test '$(cell gs-canvas.csv 3 5)' = 0 && test '$(cell gs-canvas.csv 4 5)' = 0"

# Two submissions under one SID, and a third whose SID is literally the id the clash's second one would be renamed
# to, listed after them: each keeps a row of its own, and the literal SID keeps its id and its own file (the
# reference), not the clash's.
mkdir -p gs-clash/submission_911 gs-clash/submission_912 gs-clash/submission_913
cp "$reference" gs-clash/submission_911/
cp "$starter" gs-clash/submission_912/
cp "$reference" gs-clash/submission_913/
cat >gs-clash/submission_metadata.yml <<'YML'
---
submission_911:
  :submitters:
  - :name: Sam One
    :sid: s42
submission_912:
  :submitters:
  - :name: Sam One
    :sid: s42
submission_913:
  :submitters:
  - :name: Sid Literal
    :sid: s42-submission_912
YML
run_capture gs-clash "$SIMLAB" grade apple gs-clash -o gs-clash-grades --from gradescope -j 2
check "Gradescope: three submissions, three rows, however the SIDs clash; the literal SID keeps its own file" \
  bash -c "test $(status_of gs-clash) -eq 0 && test $(rows gs-clash-grades/gradebook.csv) -eq 3 &&
           test '$(score_of gs-clash-grades s42-submission_912)' = '100 graded' &&
           test \"\$(cut -d, -f2 gs-clash-grades/gradebook.csv | sort | tr '\\n' ' ')\" = '0 100 100 score '"

# Moodle: "Full Name_participant_assignsubmission_file_" folders; an online text is the same student.
mkdir -p "moodle/Ada Lovelace_123456_assignsubmission_file_" "moodle/Ada Lovelace_123456_assignsubmission_onlinetext_" \
         "moodle/Bob Byte_123457_assignsubmission_file_"
cp "$reference" "moodle/Ada Lovelace_123456_assignsubmission_file_/"
echo "<p>see the file</p>" >"moodle/Ada Lovelace_123456_assignsubmission_onlinetext_/onlinetext.html"
cp "$starter" "moodle/Bob Byte_123457_assignsubmission_file_/"
run_capture moodle-refused "$SIMLAB" grade apple moodle -o moodle-grades
check "Moodle's download without --from: refused, naming --from moodle" \
  grep -q 'looks like a moodle download: add --from moodle' moodle-refused.err
run_capture moodle-graded "$SIMLAB" grade apple moodle -o moodle-grades --from moodle -j 2
check "Moodle: one row per student (the online text is not a second one), ids from name and number" \
  bash -c "test $(status_of moodle-graded) -eq 0 && test $(rows moodle-grades/gradebook.csv) -eq 2 &&
           test '$(score_of moodle-grades Ada-Lovelace_123456)' = '100 graded'"

# Moodle's download "not in folders": one file per upload, named after the student; its time is the submission's.
mkdir moodle-flat
cp "$reference" "moodle-flat/Ada Lovelace_123456_assignsubmission_file_NewtonsApple.cpp"
cp "$starter" "moodle-flat/Bob Byte_123457_assignsubmission_file_NewtonsApple.cpp"
echo "<p>hi</p>" >"moodle-flat/Bob Byte_123457_assignsubmission_onlinetext_onlinetext.html"
touch -d '2026-11-02 09:30:00 UTC' "moodle-flat/Ada Lovelace_123456_assignsubmission_file_NewtonsApple.cpp"
run_capture moodle-flat "$SIMLAB" grade apple moodle-flat -o moodle-flat-grades --from moodle -j 2
check "Moodle not in folders: the same students, ids and scores, and the file's time" \
  bash -c "test $(status_of moodle-flat) -eq 0 && test $(rows moodle-flat-grades/gradebook.csv) -eq 2 &&
           test '$(score_of moodle-flat-grades Ada-Lovelace_123456)' = '100 graded' &&
           test '$(score_of moodle-flat-grades Bob-Byte_123457)' = '0 graded' &&
           grep -q ',2026-11-02T09:30:00Z,Moodle.s file time,' moodle-flat-grades/roster.csv"

# gh classroom clone's folder, "<assignment>-submissions": logins that share a start keep it, and each student's
# time is their last commit's.
for who in uw-alice uw-bob; do
  repo=lab1-submissions/lab1-$who
  mkdir -p "$repo" && cp "$reference" "$repo/NewtonsApple.cpp"
  git -C "$repo" init -q && git -C "$repo" add NewtonsApple.cpp &&
    GIT_COMMITTER_DATE='2026-11-03T12:00:00+01:00' git -C "$repo" -c user.name=s -c user.email=s@x commit -qm work
done
run_capture gh-clone "$SIMLAB" grade apple lab1-submissions -o gh-grades --from classroom -j 2
check "Classroom: a shared login prefix is kept (the assignment's name is the folder's), the commit's time read" \
  bash -c "test $(status_of gh-clone) -eq 0 && test '$(score_of gh-grades uw-alice)' = '100 graded' &&
           test '$(score_of gh-grades uw-bob)' = '100 graded' &&
           grep -q '^uw-alice,.*,2026-11-03T11:00:00Z,the last commit.s time,' gh-grades/roster.csv"

# GitHub Classroom: a repository per student, the file deep inside.
for who in ada bob; do
  mkdir -p "classroom/apple-lab-$who/.git" "classroom/apple-lab-$who/starter/apple"
done
cp "$reference" classroom/apple-lab-ada/starter/apple/NewtonsApple.cpp
cp "$starter" classroom/apple-lab-bob/starter/apple/NewtonsApple.cpp
run_capture classroom-refused "$SIMLAB" grade apple classroom -o classroom-grades
check "Classroom's clones without --from: refused, naming --from classroom" \
  grep -q 'looks like a classroom download: add --from classroom' classroom-refused.err
run_capture classroom-graded "$SIMLAB" grade apple classroom -o classroom-grades --from classroom -j 2
check "Classroom: ids are the logins, the file found deep in each repository" \
  bash -c "test $(status_of classroom-graded) -eq 0 && test '$(score_of classroom-grades ada)' = '100 graded' &&
           test '$(score_of classroom-grades bob)' = '0 graded'"

# Hostile or careless downloads: two students whose ids would be alike stay apart; a submission key that is not a
# plain folder name takes nothing; a YAML alias is refused; an old attempt in a subfolder does not win over the
# file handed in; an --out inside the download, and a class folder simlab did not make, are refused.
mkdir -p odd/s1 odd/s2 odd/s3/Attempt1
cp "$starter" odd/s1/NewtonsApple.cpp && cp "$reference" odd/s2/NewtonsApple.cpp
echo '// the old attempt' >odd/s3/Attempt1/NewtonsApple.cpp && cp "$reference" odd/s3/NewtonsApple.cpp
printf '%s\n' 's1:' '  :submitters:' '  - {":name": Jo, ":email": jsmith@gmail.com}' 's2:' '  :submitters:' \
  '  - {":name": Jane, ":email": jsmith@uni.edu}' 's3:' '  :submitters:' '  - {":sid": "3"}' '".":' '  :submitters:' \
  '  - {":sid": "dot"}' >odd/submission_metadata.yml
run_capture odd "$SIMLAB" grade apple odd -o odd-grades --from gradescope -j 2
check "two students whose e-mails share a name are two rows, each graded on their own file" \
  bash -c "test '$(score_of odd-grades jsmith)' = '0 graded' && test '$(score_of odd-grades jsmith-s2)' = '100 graded'"
check "a submission key '.' takes nothing of the download (a missing file, said in the roster)" \
  bash -c "test '$(score_of odd-grades dot)' = '0 missing file' && grep -q 'no folder . in the download' odd-grades/roster.csv"
check "the file handed in wins over an old attempt in a subfolder, and the roster says so" \
  bash -c "test '$(score_of odd-grades 3)' = '100 graded' && grep -q 'another NewtonsApple.cpp nearer the top was taken' odd-grades/roster.csv"
printf '%s\n' 's1: &a' '  :submitters: [{":sid": "1"}]' 's2: *a' >odd/submission_metadata.yml
run_capture alias "$SIMLAB" grade apple odd -o alias-grades --from gradescope
check "a YAML alias: refused in one line" \
  bash -c "test $(status_of alias) -eq 2 && test \$(wc -l <alias.err) -eq 1 && grep -q 'an alias' alias.err"
run_capture inside "$SIMLAB" grade apple classroom -o classroom/grades --from classroom
check "an --out inside the download: refused in one line" \
  bash -c "test $(status_of inside) -eq 2 && grep -q 'lies in the download' inside.err && ! test -e classroom/grades/class"
mkdir -p mine/class && echo "my own notes" >mine/class/notes.txt
run_capture mine "$SIMLAB" grade apple classroom -o mine --from classroom
check "a class folder simlab did not make is refused, and kept" \
  bash -c "test $(status_of mine) -eq 2 && grep -q 'is not a class simlab took in' mine.err && test -f mine/class/notes.txt"

# Loose files are no one's folder: refused, with what to do.
mkdir loose && cp "$reference" loose/ada.cpp && cp "$starter" loose/bob.cpp
run_capture loose "$SIMLAB" grade apple loose -o loose-grades
check "a folder of loose files: refused in one line, naming a folder per student and --from" \
  bash -c "test $(status_of loose) -eq 2 && grep -q 'holds files, not a folder per student' loose.err &&
           test \$(wc -l <loose.err) -eq 1"
run_capture wrong "$SIMLAB" grade apple loose -o wrong-grades --from gradescope
check "--from a platform the folder is not: one line" \
  bash -c "test $(status_of wrong) -eq 2 && test \$(wc -l <wrong.err) -eq 1 && grep -q 'submission_metadata.yml' wrong.err"
finish
