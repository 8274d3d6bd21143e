# A grade does not depend on load: the same class - the cases whose outcome CPU time or a count of processes decides
# (an endless loop, CPU time to spare, a fork bomb, memory, a search of the disk) and a few whose physics passes or
# fails by digits - graded on an idle machine and beside four CPU-bound processes gets identical scores and outcomes:
# a busy machine makes no CPU-bound test "stalled". (Size proves nothing here: the whole sample class is graded by
# cli/grade-sample-class; a sleeper, stalled by the wall clock alone, by corpus/apple/hostile-class.)
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

mkdir class
corpus=$SOURCE_DIR/tests/corpus/apple
"$CORPUS" materialize apple "$corpus"/{reference,infinite-loop,euler-coarse-step,trade-too-few-digits}.toml \
  "$corpus"/hostile/{read-other-students,spin-forever,fork-bomb,allocate-until-killed}.toml --out class
scores() {  # each student's row, and each test's outcome from results.json
  tail -n +2 "$1/gradebook.csv"
  for f in "$1"/students/*/results.json; do
    echo "${f%/results.json}" | sed 's|.*/||'; grep -o '"outcome": "[^"]*"' "$f"
  done
}

SECONDS=0
run_capture idle "$SIMLAB" grade apple class --out idle --jobs 2
idle_seconds=$SECONDS
check "graded on an idle machine" test "$(status_of idle)" -eq 0

hogs=()
for _ in 1 2 3 4; do (while :; do :; done) & hogs+=($!); done
SECONDS=0
run_capture busy "$SIMLAB" grade apple class --out busy --jobs 2
busy_seconds=$SECONDS
kill "${hogs[@]}"
wait "${hogs[@]}" 2>/dev/null
check "graded beside four CPU-bound processes" test "$(status_of busy)" -eq 0
echo "idle: ${idle_seconds} s; beside four CPU-bound processes: ${busy_seconds} s"
scores idle >idle.scores
scores busy >busy.scores
check "the gradebooks are identical" cmp -s idle/gradebook.csv busy/gradebook.csv
check "every test's outcome is identical" cmp -s idle.scores busy.scores
diff idle.scores busy.scores | head -20
finish
