# Points given by hand belong to the file they were given to: simlab grade fills in manual.csv's file column the
# first time it reads points there; when the student's file changes, the points are kept and counted but flagged as
# given to an earlier file (report.html, one line at the end of the run, the feedback, results.json) until the
# instructor clears the cell; a student whose file did not change is not flagged. results.json's text says the
# points given, not "pending". A sheet without the file column (an older simlab's) still reads.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
cell() { python3 -c 'import csv,sys; print(list(csv.reader(open(sys.argv[1])))[int(sys.argv[2])][int(sys.argv[3])])' "$@"; }
content() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["content"])' "grades/students/$1/record.json"; }
output_of() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["output"])' "grades/students/$1/results.json"; }
grade() { "$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml >"$1.out" 2>&1; }
one="the write-up explains the step size"
two="the plot is labelled"
line="manual grades were given to an earlier file: see grades/report.html"

# The apple's rubric cut to its first test (cheap to grade), with two items graded by hand.
python3 - "$SOURCE_DIR/assignments/apple/grading/rubric.toml" <<'EOF' >rubric.toml
import sys
head, first, *rest = open(sys.argv[1]).read().split("\n[[test]]")
print(head + "\n[[test]]" + first)
EOF
printf '\n[[manual]]\nname = "%s"\npoints = 20\n\n[[manual]]\nname = "%s"\npoints = 10\n' "$one" "$two" >>rubric.toml
mkdir -p class/ada class/bob
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/ada/
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/bob/
grade first
check "graded; manual.csv has the file column, empty while the points are" \
  bash -c "test '$(head -1 grades/manual.csv)' = 'student,item,points,comment,file' && test -z '$(cell grades/manual.csv 1 4)'"
check "results.json says the items are pending" bash -c "grep -q 'Graded by hand, pending: 30 points' <<<'$(output_of ada)'"

# Points given in a sheet of the old form (no file column).
printf 'student,item,points,comment\nada,%s,7.5,"the step, not the tolerance"\nada,%s,10,\nbob,%s,12,\nbob,%s,,\n' \
  "$one" "$two" "$one" "$two" >grades/manual.csv
grade given
check "the old sheet reads; each row with points gets the file it was given to, a pending row none" \
  bash -c "test '$(cell grades/manual.csv 1 4)' = '$(content ada)' && test '$(cell grades/manual.csv 2 4)' = '$(content ada)' &&
           test '$(cell grades/manual.csv 3 4)' = '$(content bob)' && test -z '$(cell grades/manual.csv 4 4)' &&
           test \$(wc -c <<<'$(content ada)') -eq 13"
check "nothing is flagged while the files are the same" \
  bash -c "! grep -q 'earlier file' given.out && ! grep -q 'earlier-file' grades/report.html"
check "results.json's text says the points given, and nothing pending, once every item has its points" \
  bash -c "grep -q 'Graded by hand: 17.5/30 points' <<<'$(output_of ada)' && ! grep -q pending <<<'$(output_of ada)'"
check "bob's says his points and his item still pending" \
  bash -c "grep -q 'Graded by hand: 12/20 points' <<<'$(output_of bob)' &&
           grep -q 'Graded by hand, pending: 10 points' <<<'$(output_of bob)'"

# Ada hands in another file.
echo "// handed in again" >>class/ada/NewtonsApple.cpp
grade resubmitted
check "the run says, in one line, that her 2 grades were given to an earlier file" \
  bash -c "test \$(grep -c 'earlier file' resubmitted.out) -eq 1 && grep -q '^2 $line\$' resubmitted.out"
check "her points are kept in manual.csv with the earlier file, and still count: 27.5/40" \
  bash -c "grep -q '^ada,$one,7.5,' grades/manual.csv && test '$(cell grades/manual.csv 1 4)' != '$(content ada)' &&
           test '$(cell grades/gradebook.csv 1 1)' = 27.5 && test '$(cell grades/gradebook.csv 1 2)' = 40"
check "report.html lists her two items with their points, and not bob's" python3 -c '
import re, sys
page = open("grades/report.html").read()
section = re.search(r"<section id=\"earlier-file\">(.*?)</section>", page, re.S)
rows = re.findall(r"<tr><td class=\"name\"><a [^>]*>(\w+)</a></td><td class=\"name\">([^<]*)</td><td class=\"num\">([^<]*)</td>",
                  section.group(1) if section else "")
sys.exit(not ("Manual points given to an earlier file" in page and
              sorted(rows) == sorted([("ada", sys.argv[1], "7.5/20"), ("ada", sys.argv[2], "10/10")])))' "$one" "$two"
check "her feedback and results.json flag them; bob's do not" python3 -c '
import json, sys
ada = json.load(open("grades/students/ada/results.json"))["extra_data"]["manual_graded"]
bob = json.load(open("grades/students/bob/results.json"))["extra_data"]["manual_graded"]
sys.exit(not (all(m["earlier_file"] for m in ada) and len(ada) == 2 and not any(m["earlier_file"] for m in bob) and
              "given to an earlier version of your file" in open("grades/students/ada/feedback.md").read() and
              "earlier version" not in open("grades/students/bob/feedback.md").read()))'

# The instructor confirms ada's points (clears the cells); bob gives his second item points and hands in another
# file before the next run: those points were given to the file he had, like his first item's.
python3 - "$two" <<'EOF'
import csv, sys
rows = list(csv.reader(open("grades/manual.csv")))
for r in rows[1:]:
    if r[0] == "ada": r[4] = ""
    if r[0] == "bob" and r[1] == sys.argv[1]: r[2] = "5"
csv.writer(open("grades/manual.csv", "w", newline="")).writerows(rows)
EOF
echo "// handed in again" >>class/bob/NewtonsApple.cpp
grade confirmed
check "ada's points are for her file now, and no longer flagged; bob's two are" \
  bash -c "test '$(cell grades/manual.csv 1 4)' = '$(content ada)' && grep -q '^2 $line\$' confirmed.out &&
           ! grep -q 'given to an earlier' grades/students/ada/feedback.md &&
           test \$(grep -c 'given to an earlier version' grades/students/bob/feedback.md) -eq 2"

# A file cell simlab did not write: one line, exit 2.
sed -i '2s/,[0-9a-f]*$/,not-a-hash/' grades/manual.csv
run_capture badfile "$SIMLAB" grade apple class -o grades -j 2 --rubric rubric.toml
check "a file cell that is not a hash stops simlab in one line" \
  bash -c "test $(status_of badfile) -eq 2 && test \$(wc -l <badfile.err) -eq 1 && grep -q 'not one simlab wrote' badfile.err"
finish
