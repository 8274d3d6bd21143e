# A grade does not depend on load: the same class - the cases whose outcome CPU time or a count of processes decides
# (an endless loop, CPU time to spare, a fork bomb, memory, a search of the disk) and a few whose physics passes or
# fails by digits - graded beside four CPU-bound processes gets every score, outcome and report the corpus expects of
# it, which is what an idle machine gives (the corpus tests and the class runs grade the same cases idle): a busy
# machine makes no CPU-bound test "stalled". (Size proves nothing here: the whole sample class is graded by
# cli/grade-sample-class; a sleeper, stalled by the wall clock alone, by corpus/apple/hostile-class.)
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

mkdir class
corpus=$SOURCE_DIR/tests/corpus/apple
cases=("$corpus"/{reference,infinite-loop,euler-coarse-step,trade-too-few-digits}.toml
       "$corpus"/hostile/{read-other-students,spin-forever,fork-bomb,allocate-until-killed}.toml)
"$CORPUS" materialize apple "${cases[@]}" --out class
hogs=()
for _ in 1 2 3 4; do (while :; do :; done) & hogs+=($!); done
SECONDS=0
run_capture busy "$SIMLAB" grade apple class --out busy --jobs 2
busy_seconds=$SECONDS
kill "${hogs[@]}"
wait "${hogs[@]}" 2>/dev/null
check "graded beside four CPU-bound processes (${busy_seconds} s)" test "$(status_of busy)" -eq 0
run_capture compare "$CORPUS" compare apple "${cases[@]}" --grades busy
check "every score, every test's outcome and every report are the corpus's own, as on an idle machine" \
  test "$(status_of compare)" -eq 0
[[ $(status_of compare) -eq 0 ]] || head -n 20 compare.out
finish
