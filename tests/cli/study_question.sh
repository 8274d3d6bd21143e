# simlab study trade LAB --question: the question's sweeps, measured side by side, come back in the order one run
# prints them; a progress line says how far the study has come, numbered point by point up to the last; each point is
# stopped at the grader's cap on an answer, and one short of the digits asked for from its first start is measured
# from that start alone; a student's file (the solution's copy) gives the same figures from grading's sandbox.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

# progress_ok FILE TOTAL: FILE's lines "  point n of N measured ..." all have N = TOTAL, never count down, and end
# with "point TOTAL of TOTAL measured, in S s".
progress_ok() {
  awk -v total="$2" '
    /^  point [0-9]+ of [0-9]+ measured/ {
      lines++
      if ($4 != total || $2 + 0 < last || $2 + 0 > total) bad = 1
      last = $2 + 0
      final = $0
    }
    END { exit !(lines >= 1 && !bad && last == total && final ~ /measured, in [0-9]+ s$/) }' "$1"
}
# The order one run prints its points in: each integrator's accuracies, then each one's fixed steps.
sweeps() { tail -n +2 "$1" | cut -d, -f3,4 | uniq | tr '\n' ' '; }
integrators="RungeKuttaMerson RungeKutta3 RungeKutta2 RungeKuttaFeldberg ExplicitEuler SemiExplicitEuler SemiExplicitEuler2 Verlet"
expected=""
for i in $integrators CPodes; do expected+="$i,accuracy "; done
for i in $integrators; do expected+="$i,fixed step "; done

run_capture projectile "$SIMLAB" study trade projectile --question --quick --no-plots -o pq
check "the projectile's question study succeeds with its 158 points" \
  bash -c "test $(status_of projectile) -eq 0 && test \$(tail -n +2 pq/trade.csv | wc -l) -eq 158"
check "its progress lines count the points up to 158 of 158" progress_ok projectile.err 158
check "its points come in the order one run prints them, each sweep once" test "$(sweeps pq/trade.csv)" = "$expected"
check "it names the grader's cap on an answer: 10 times the front's cost at 12 digits (296 evaluations)" \
  grep -q "^Each point is stopped past 296 evaluations, where the grader stops an answer" projectile.out
check "and no point measured past it counts: every ok point within 296 evaluations, the others too costly" \
  awk -F, 'NR > 1 { if ($7 == "ok" && $15 > 296) bad = 1; if ($7 == "too costly") costly++ }
           END { exit !(!bad && costly > 0) }' pq/trade.csv

# The book at a cap of 5000 evaluations: long enough for several progress lines, short enough for a test.
run_capture book "$SIMLAB" study trade book --question --quick --no-plots --max-evaluations 5000 -o bq
check "the book's question study succeeds with its 158 points" \
  bash -c "test $(status_of book) -eq 0 && test \$(tail -n +2 bq/trade.csv | wc -l) -eq 158"
check "its points come in the order one run prints them, each sweep once" test "$(sweeps bq/trade.csv)" = "$expected"
check "its progress lines count the points up to 158 of 158" progress_ok book.err 158
check "a point short of 8 digits is measured from its first start alone, one that keeps them from every start" \
  awk -F, 'NR > 1 && $7 == "ok" { alone = $0 ~ /measured from that start alone/
                                   if ($10 >= 8 && alone) bad = 1; if ($10 < 8 && !alone) bad = 1; if (alone) n++ }
           END { exit !(!bad && n > 0) }' bq/trade.csv

cp "$SOURCE_DIR/solutions/book/BookSpin.cpp" .
run_capture file "$SIMLAB" study trade book --question --quick --no-plots --max-evaluations 5000 --file BookSpin.cpp -o bf
check "--file on the solution's BookSpin.cpp: the same points from grading's sandbox, the same progress" \
  bash -c "test $(status_of file) -eq 0 && diff <(cut -d, -f1-15,17- bq/trade.csv) <(cut -d, -f1-15,17- bf/trade.csv) >/dev/null"
check "and its progress lines count the points up to 158 of 158" progress_ok file.err 158

run_capture sweep "$BIN_DIR/book-study" --quick --sweep 99
check "a sweep the study does not have is an error in one line" \
  bash -c "test $(status_of sweep) -ne 0 && grep -q 'the study has only 17 sweeps (0 to 16)' sweep.err"
finish
