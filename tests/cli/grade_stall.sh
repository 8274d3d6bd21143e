# A submission that sleeps in the code every test runs first (building the model) pays the wall-clock net once: the
# first test to stall waits the rubric's 30 s, and each later one is stopped as soon as neither its code nor its judge
# makes progress. Graded as a class and by simlab autograde (Gradescope's and PrairieLearn's entry point): every test
# is "stalled", the score is 0, exactly one test waited the whole net (in a class, where a submission has one judge),
# and no report says "stalled: stalled". The wall times are printed, not asserted (a busy machine is slower, not
# wrong).
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

sleeper=$SOURCE_DIR/tests/corpus/apple/hostile/sleep-in-every-test.toml
mkdir class
"$CORPUS" materialize apple "$sleeper" --out class
# How many of results.json's tests waited the whole net, and how many were stopped once another had.
count() { grep -o "$2" "$1" | wc -l; }

SECONDS=0
run_capture grade "$SIMLAB" grade apple class --out grades --jobs 1
echo "a class of one sleeper: ${SECONDS} s"
results=grades/students/sleep-in-every-test/results.json
check "the class is graded" test "$(status_of grade)" -eq 0
check "exactly one test waited the whole wall-clock net" test "$(count "$results" 'no end after 30 s of wall-clock')" -eq 1
check "the other twelve were stopped once it had" test "$(count "$results" 'had already waited the full 30 s')" -eq 12
check "no report repeats the outcome" \
  bash -c '! grep -rq "stalled: stalled\|timed out: timed out" grades grade.out'
"$CORPUS" compare apple "$sleeper" --grades grades >compare.out 2>&1
check "the score (0), every outcome (stalled) and the report are the corpus's own" test $? -eq 0

# As many judges as cores, each starting on a test at once: those first tests may all wait the net together.
judges=$(getconf _NPROCESSORS_ONLN)
SECONDS=0
run_capture autograde "$SIMLAB" autograde apple --submission class/sleep-in-every-test --results results.json
echo "simlab autograde ($judges judges): ${SECONDS} s, $(count results.json 'no end after 30 s') test(s) waited the whole net"
check "autograde writes its results.json" test "$(status_of autograde)" -eq 0
check "autograde: every test stalled, and no more waited the whole net than there are judges" \
  test "$(count results.json '"stalled: ')" -eq 13 -a "$(count results.json 'no end after 30 s')" -le "$judges"
finish
