# simlab export canvas: a graded class and a roster become the CSV Canvas's gradebook import takes for one
# assignment column, with the points simlab check --all gives; who is missing on either side is said; a bad
# roster is one line and a non-zero exit.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
points() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["score"])' "$1"; }
# cell FILE ROW COLUMN: one cell of a CSV file, as a CSV reader reads it
cell() { python3 -c 'import csv,sys; print(list(csv.reader(open(sys.argv[1])))[int(sys.argv[2])][int(sys.argv[3])])' "$@"; }

hostile='=cmd|x!A0'
mkdir -p class/ada class/bob "class/$hostile" class/dan
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/ada/
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" class/bob/
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" class/dan/
"$SIMLAB" grade apple class -o grades -j 2 >grade.out 2>&1
check "the class is graded" test -f grades/students/ada/record.json -a -f grades/students/bob/record.json
"$SIMLAB" check apple "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" --all --format json >reference.json
"$SIMLAB" check apple "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" --all --format json >starter.json

cat >roster.csv <<'EOF'
Student,ID,SIS User ID,SIS Login ID,Section,simlab id
"Lovelace, Ada",101,s101,ada1,Lab A,ada
=HYPERLINK("http://x"),102,s102,bob2,"Lab A,Lab B",bob
"Carol, C",103,s103,carol3,Lab B,carol
EOF
run_capture export "$SIMLAB" export canvas apple --grades grades --roster roster.csv -o canvas.csv --canvas-id 4242
check "export canvas succeeds" test "$(status_of export)" -eq 0
check "Canvas's header: its five columns, then the assignment named with its id" \
  test "$(head -1 canvas.csv)" = "Student,ID,SIS User ID,SIS Login ID,Section,Newton's apple (4242)"
check "the Points Possible row, as Canvas exports it" test "$(sed -n 2p canvas.csv)" = "Points Possible,,,,,100"
check "one row per roster student, in its order" test "$(wc -l <canvas.csv)" -eq 5
check "the reference's points are those of simlab check --all" test "$(cell canvas.csv 2 5)" = "$(points reference.json | sed 's/\.0$//')"
check "the starter's too" test "$(cell canvas.csv 3 5)" = "$(points starter.json | sed 's/\.0$//')"
check "a name with a comma stays one cell" test "$(cell canvas.csv 2 0)" = "Lovelace, Ada"
check "a formula in a name is neutralized" test "$(cell canvas.csv 3 0)" = "'=HYPERLINK(\"http://x\")"
check "Canvas's ids are kept" test "$(cell canvas.csv 2 1),$(cell canvas.csv 2 2),$(cell canvas.csv 2 3)" = "101,s101,ada1"
check "a roster student without a folder has a blank cell (Canvas keeps its grade)" test "$(sed -n 5p canvas.csv)" = "\"Carol, C\",103,s103,carol3,Lab B,"
check "and is said" grep -q "1 on the roster without a grade .*: carol" export.err
check "graded folders not on the roster are said, the hostile one printable" \
  grep -q "2 graded but not on the roster (left out of the file): =cmd|x!A0, dan" export.err

cat >logins.csv <<'EOF'
Student,ID,SIS Login ID,Section,Newton's apple (4242)
Points Possible,,,,100
"Lovelace, Ada",101,ada,Lab A,
EOF
run_capture logins "$SIMLAB" export canvas apple --grades grades --roster logins.csv -o logins-out.csv --name "Lab 1"
check "a Canvas export is a roster: no simlab id column, the SIS Login ID is the folder" \
  bash -c "test $(status_of logins) -eq 0 && test \"\$(sed -n 3p logins-out.csv)\" = '\"Lovelace, Ada\",101,,ada,Lab A,100' &&
           test \"\$(head -1 logins-out.csv)\" = 'Student,ID,SIS User ID,SIS Login ID,Section,Lab 1'"

bad() {  # bad NAME TEXT WHAT: a roster holding TEXT is refused in one line saying WHAT
  printf '%b' "$2" >"$1.csv"
  run_capture "$1" "$SIMLAB" export canvas apple --grades grades --roster "$1.csv" -o "$1-out.csv"
  check "bad roster ($1): one line, exit 2" \
    bash -c "test $(status_of "$1") -eq 2 && test \$(wc -l <$1.err) -eq 1 && grep -q '$3' $1.err && ! test -e $1-out.csv"
}
bad no-student 'Name,ID,simlab id\nAda,1,ada\n' 'no Student column'
bad no-id 'Student,Section,simlab id\nAda,A,ada\n' 'none of the columns ID, SIS User ID and SIS Login ID'
bad open-quote 'Student,ID,simlab id\n"Ada,1,ada\n' 'never closed'
bad nobody 'Student,ID,simlab id\n,,ada\n' 'names no student'
bad empty '' 'is empty'
# A group's folder named on each member's row, a student simlab has no id for, a folder with no file in it.
mkdir -p class/eve && echo "my notes" >class/eve/README.txt
"$SIMLAB" grade apple class -o grades -j 2 >regrade.out 2>&1
printf '%s\n' 'Student,ID,SIS User ID,SIS Login ID,Section,simlab id' 'Fay,201,s201,fay,Lab A,dan' \
  'Gus,202,s202,gus,Lab A,dan' 'Hal,203,s203,hal,Lab A,' 'Eve,204,s204,eve,Lab A,eve' >groups.csv
run_capture groups "$SIMLAB" export canvas apple --grades grades --roster groups.csv -o groups-out.csv
starter_points=$(points starter.json | sed 's/\.0$//')
check "a group's members each get the group's grade" \
  bash -c "test $(status_of groups) -eq 0 && test '$(cell groups-out.csv 2 5)' = '$starter_points' &&
           test '$(cell groups-out.csv 3 5)' = '$starter_points'"
check "a student with no simlab id: a blank cell, and said" \
  bash -c "test -z '$(cell groups-out.csv 4 5)' && grep -q '1 on the roster without a simlab id .*: Hal' groups.err"
check "a folder with no file: a blank cell, never a 0, and said" \
  bash -c "test -z '$(cell groups-out.csv 5 5)' && grep -q '1 handed in no file to grade (blank, not 0' groups.err"

run_capture nofile "$SIMLAB" export canvas apple --grades grades --roster missing.csv -o x.csv
check "no roster file: one line" bash -c "test $(status_of nofile) -ne 0 && test \$(wc -l <nofile.err) -eq 1"
run_capture nogrades "$SIMLAB" export canvas apple --grades nowhere --roster roster.csv -o x.csv
check "no graded class: one line that says to grade first" \
  bash -c "test $(status_of nogrades) -eq 2 && grep -q 'run simlab grade apple first' nogrades.err"
run_capture badid "$SIMLAB" export canvas apple --grades grades --roster roster.csv -o x.csv --canvas-id 12x
check "a Canvas id that is not a number: one line" bash -c "test $(status_of badid) -eq 2 && test \$(wc -l <badid.err) -eq 1"
finish
