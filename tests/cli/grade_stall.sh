# The apple's hostile cases that stall (their outcomes say "stalled": tests/CMakeLists.txt passes them, and leaves
# them out of corpus/apple/hostile-class), graded as one class with every check a hostile class gets
# (simlab-corpus class), and, at the same time, the sleeper by simlab autograde (Gradescope's and PrairieLearn's
# entry point): the suite waits the wall-clock net once. A submission that sleeps in the code every test runs first
# (building the model) pays the net once: the first test to stall waits the rubric's 30 s, and each later one is
# stopped as soon as neither its code nor its judge makes progress. Every test is "stalled", the score is 0, exactly
# one test waited the whole net (in a class, where a submission has one judge), and no report says
# "stalled: stalled". The wall times are printed, not asserted (a busy machine is slower, not wrong).
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

sleeper=$SOURCE_DIR/tests/corpus/apple/hostile/sleep-in-every-test.toml
check "the sleeper is among the stalling cases" bash -c 'for c in "${@:2}"; do [[ $c == "$1" ]] && exit 0; done; exit 1' \
  _ "$sleeper" "$@"
mkdir one
"$CORPUS" materialize apple "$sleeper" --out one
# How many of results.json's tests waited the whole net, and how many were stopped once another had.
count() { grep -o "$2" "$1" | wc -l; }
# As many judges as cores, each starting on a test at once: those first tests may all wait the net together.
judges=$(getconf _NPROCESSORS_ONLN)

SECONDS=0
"$CORPUS" class apple "$@" --simlab "$SIMLAB" --jobs 2 --keep grades >class.out 2>&1 </dev/null &
class=$!
run_capture autograde "$SIMLAB" autograde apple --submission one/sleep-in-every-test --results results.json
wait "$class"
echo $? >class.status
echo "the stalling cases as a class and the sleeper by simlab autograde ($judges judges), side by side: ${SECONDS} s"
cat class.out

check "the class: every student's score, outcomes and report are the corpus's own, and the class's checks pass" \
  test "$(status_of class)" -eq 0
results=grades/students/sleep-in-every-test/results.json
check "  the sleeper: exactly one test waited the whole wall-clock net" \
  test "$(count "$results" 'no end after 30 s of wall-clock')" -eq 1
check "  the other twelve were stopped once it had" test "$(count "$results" 'had already waited the full 30 s')" -eq 12
check "  no report repeats the outcome" bash -c '! grep -rq "stalled: stalled\|timed out: timed out" grades class.out'

check "autograde writes its results.json" test "$(status_of autograde)" -eq 0
check "autograde: every test stalled, and no more waited the whole net than there are judges" \
  test "$(count results.json '"stalled: ')" -eq 13 -a "$(count results.json 'no end after 30 s')" -le "$judges"
check "  no result repeats the outcome" bash -c '! grep -q "stalled: stalled\|timed out: timed out" results.json autograde.out'
finish
