# A course's staff on one machine, as docs/instructors.md sets it up: the grader (here root) grades into the staff
# group's setgid folder with umask 002; every output is the group's, as the umask gives it, and a TA of the group
# fills in manual.csv in place; the next run, under sudo's umask 022, applies the points and leaves the sheet the
# TA's to edit. A TA who runs simlab grade --from as themselves, where the judges are closed to them, is refused in
# one line before anything is written, and the grader's next run takes the download in as if they had never tried.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

if [[ $(id -u) -ne 0 ]] || ! command -v setpriv >/dev/null; then
  echo "skipped: needs root and setpriv, to act as a TA"
  exit 77
fi
staff=65530 ta=65533  # the course's own group, and a TA in it (numbers no account of the system has)
as_ta() { setpriv --reuid=$ta --regid=$staff --clear-groups env HOME="$work/ta" XDG_CACHE_HOME="$work/ta/cache" "$@"; }
cell() { python3 -c 'import csv,sys; print(list(csv.reader(open(sys.argv[1])))[int(sys.argv[2])][int(sys.argv[3])])' "$@"; }
chmod 0755 "$work"
mkdir -p ta && chown $ta:$staff ta
item="the write-up explains the step size"
cp "$SOURCE_DIR/assignments/apple/grading/rubric.toml" rubric.toml
printf '\n[[manual]]\nname = "%s"\npoints = 20\n' "$item" >>rubric.toml
mkdir -p class/ada && cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/ada/
install -d -g $staff -m 2775 grades

(umask 002 && "$SIMLAB" grade apple class -o grades/apple --rubric rubric.toml >first.out 2>&1)
check "graded into the staff's folder: the grades folder is the group's alone, its outputs the group's, writable by it" \
  bash -c "test \"\$(stat -c '%a %g' grades/apple)\" = '2770 $staff' &&
           test \"\$(stat -c '%a %g' grades/apple/manual.csv grades/apple/gradebook.csv grades/apple/report.html | sort -u)\" = '664 $staff' &&
           test \"\$(stat -c '%a %g' grades/apple/students/ada/feedback.html)\" = '664 $staff'"
run_capture ta-edit as_ta python3 -c '
import sys
path, item = sys.argv[1], sys.argv[2]
with open(path, "r+") as sheet:  # in place, as an editor saves it
    text = sheet.read().replace("ada," + item + ",,", "ada," + item + ",15,clear")
    sheet.seek(0)
    sheet.truncate()
    sheet.write(text)' grades/apple/manual.csv "$item"
check "a TA of the group fills in manual.csv in place" \
  bash -c "test $(status_of ta-edit) -eq 0 && grep -q '^ada,$item,15,clear' grades/apple/manual.csv"
(umask 022 && "$SIMLAB" grade apple class -o grades/apple --rubric rubric.toml >second.out 2>&1)
check "the next run (sudo's umask 022) applies the points: 115" test "$(cell grades/apple/gradebook.csv 1 1)" = 115
check "  and manual.csv, written again, is still the group's to edit" \
  test "$(stat -c '%a %g' grades/apple/manual.csv)" = "664 $staff"
run_capture ta-again as_ta bash -c "echo >>grades/apple/manual.csv"
check "  as the TA finds it" test "$(status_of ta-again)" -eq 0

# The judges closed to others, as scripts/lock-course leaves them: a manifest whose judge the TA may not read.
mkdir -m 0711 judges
python3 - "$BIN_DIR/../simlab-build.json" "$work/judges" <<'PY'
import json, shutil, sys
manifest = json.load(open(sys.argv[1]))
for a in manifest["assignments"]:
    if a["id"] == "apple":
        a["judge"] = shutil.copy(a["judge"], sys.argv[2] + "/apple-judge")
json.dump(manifest, open("closed.json", "w"))
PY
chmod 0644 closed.json && chmod 0700 judges/apple-judge
mkdir canvas && cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" canvas/lovelaceada_101_9001_NewtonsApple.cpp
mkdir -p shared && chgrp $staff shared && chmod 2775 shared
run_capture ta-grade as_ta env SIMLAB_MANIFEST="$work/closed.json" "$SIMLAB" grade apple canvas -o shared/apple --from canvas
check "a TA's own simlab grade --from: refused in one line naming the account to grade as" \
  bash -c "test $(status_of ta-grade) -eq 2 && test \$(wc -l <ta-grade.err) -eq 1 &&
           grep -q \"judge .* is for $(id -un) alone to read\" ta-grade.err"
check "  before anything was written: no grades folder, no class taken in" \
  bash -c "test -z \"\$(ls -A shared)\""
run_capture grader env SIMLAB_MANIFEST="$work/closed.json" "$SIMLAB" grade apple canvas -o shared/apple --from canvas
check "the grader's next run takes the download in and grades it" \
  bash -c "test $(status_of grader) -eq 0 && grep -q '^1 graded' grader.out"
finish
