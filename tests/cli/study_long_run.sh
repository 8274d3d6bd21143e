# simlab study long-run, the quick view (20 s) of the book and the baby boot: the energy's drift and the
# trajectory's digits hold the physics each figure is there to show. Verlet's fixed step keeps the energy's error
# bounded where RungeKuttaMerson's grows with time; the energy keeps many more digits than the trajectory; the
# chaotic boot loses its trajectory in seconds with its energy still good to many digits. The CSV, the figure and
# the table are made, and every number printed is finite; bad input is a one-line error.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

run_capture book "$SIMLAB" study long-run book --quick -o view
run_capture boot "$SIMLAB" study long-run biosim --quick -o view
for run in book boot; do
  check "simlab study long-run ($run) --quick ends well" test "$(status_of $run)" -eq 0
done
for lab in book biosim; do
  check "$lab-long-run.csv has each of the 3 settings sampled to the final time, 20 s" \
    awk -F, -v lab="$lab" 'NR > 1 && $1 == lab && $5 + 0 == 20 { n++ } END { exit n != 3 }' "view/$lab-long-run.csv"
  if command -v gnuplot >/dev/null; then
    check "$lab-long-run.svg is drawn" grep -q '<svg' "view/$lab-long-run.svg"
  fi
done
check "no NaN or Inf reaches the tables or the CSVs" \
  bash -c "! grep -qiE '(^|[^a-z])(nan|-?inf)([^a-z]|$)' book.out boot.out view/book-long-run.csv view/biosim-long-run.csv"

# at LAB STEPPING T COLUMN: a figure of LAB's CSV for the setting whose stepping is STEPPING, at the sample at T s.
at() {
  awk -F, -v lab="$1" -v s="$2" -v t="$3" -v c="$4" \
    'NR > 1 && $1 == lab && $3 == s && $5 + 0 == t + 0 { print $c; found = 1 } END { exit !found }' \
    "view/$1-long-run.csv"
}
# Columns: 5 t_s, 7 energy_drift_largest (up to t), 8 trajectory_digits.
# Merson keeps each step's error under the accuracy but not its sign: the energy's error adds up, about tenfold from
# 1 s to 20 s on the book. Verlet, time-reversible, oscillates about a nearby conserved energy: over these 20 s its
# drift is no larger at the end than at 1 s (and over 100 s on the book, below).
verlet='fixed step 0.001 s at accuracy 1e-09'
energy_drifts() {  # energy_drifts LAB FACTOR: Merson's drift at 1e-6 grows FACTOR-fold or more, Verlet's does not
  local m1 m20 v1 v20
  m1=$(at "$1" 'accuracy 1e-06' 1 7) m20=$(at "$1" 'accuracy 1e-06' 20 7)
  v1=$(at "$1" "$verlet" 1 7) v20=$(at "$1" "$verlet" 20 7)
  check "$1's energy drifts under Merson at 1e-6: its largest drift grows $2-fold or more, 1 s to 20 s" \
    awk "BEGIN { exit !($m20 >= $2 * $m1) }"
  check "and not under Verlet at 1 ms steps over those 20 s: within 1.5 times its 1 s drift, under 1e-4" \
    awk "BEGIN { exit !($v20 <= 1.5 * $v1 && $v20 < 1e-4) }"
}
energy_drifts book 5
energy_drifts biosim 2
check "the book's energy keeps 5 digits or more at 20 s under Merson at 1e-6 where its w_B keeps fewer than 3" \
  awk "BEGIN { exit !($(at book 'accuracy 1e-06' 20 7) < 1e-5 && $(at book 'accuracy 1e-06' 20 8) < 3) }"
check "and Merson at 1e-9 keeps 3 digits more of w_B than at 1e-6, at 20 s" \
  awk "BEGIN { exit !($(at book 'accuracy 1e-09' 20 8) >= $(at book 'accuracy 1e-06' 20 8) + 3) }"

# The boot is chaotic: a difference of one step's error doubles every second or so, whatever the accuracy, while
# each step still keeps the energy to the accuracy asked.
check "each setting of the boot loses its trajectory (under 1 digit against its tighter run) within 20 s" \
  awk -F, 'NR > 1 && $8 < 1 && !($3 in lost) { lost[$3] = $5 } END { exit length(lost) != 3 }' view/biosim-long-run.csv
check "while its energy still keeps 4 digits or more there (Merson at 1e-9: 8 or more)" \
  awk -F, -v verlet="$verlet" 'NR > 1 && $8 < 1 && !($3 in lost) { lost[$3] = $7 }
           END { exit !(length(lost) == 3 && lost["accuracy 1e-06"] < 1e-4 && lost[verlet] < 1e-4 &&
                        lost["accuracy 1e-09"] < 1e-8) }' view/biosim-long-run.csv
check "the tables give each setting's drift at 1, 10 and 20 s and when its trajectory fell below 1 digit" \
  bash -c "grep -q 'drift 1 s  drift 10 s  drift 20 s' book.out && test \$(grep -cE '^  (RungeKuttaMerson|Verlet),.* by [0-9.]+ s ' boot.out) -eq 3"
check "and say what each trajectory is judged against" \
  bash -c "grep -q 'against Euler.s equations in long double' book.out && grep -q 'accuracy 1e-10' boot.out &&
           grep -q 'fixed step 0.0005 s at accuracy 1e-09' boot.out"

# Sampling cuts no step: each sample is the state at the first of the run's own step ends at or after its time
# (column 9): Verlet's at the time itself, a whole number of its 1 ms steps; Merson's within one of its steps.
for lab in book biosim; do
  check "$lab's samples are its runs' own step ends: Verlet's at the sample times, Merson's at or just after them" \
    awk -F, -v verlet="$verlet" 'NR > 1 { late = $9 - $5
      if ($3 == verlet && (late < -1e-12 * $5 || late > 1e-12 * $5)) bad = 1
      if ($3 != verlet && (late < -1e-12 * $5 || late > 0.1 + 0.1 * $5)) bad = 1 }
      END { exit bad }' "view/$lab-long-run.csv"
done

# The book's Verlet energy over 100 s: a fixed step of 1 ms whose implicit velocity update is solved to 1e-9 keeps
# its drift at its first second's (4.2e-6 of K). Solved only to 1e-3 (Simbody's default) it grew past 50 s (6.9e-6
# at 100 s): a run that said it was Verlet at a fixed step was partly something else.
run_capture book100 "$SIMLAB" study long-run book --final-time 100 --no-plots -o view100
check "over 100 s the book's Verlet drift stays within 1.05 times its drift at 1 s" \
  bash -c "test $(status_of book100) -eq 0 &&
    awk -F, -v verlet='$verlet' 'NR > 1 && \$3 == verlet && \$5 + 0 == 1 { a = \$7 }
                                 NR > 1 && \$3 == verlet && \$5 + 0 == 100 { b = \$7 }
                                 END { exit !(a > 0 && b <= 1.05 * a) }' view100/book-long-run.csv"

# Why the view names Verlet's accuracy: the book program at the same 1 ms step for 100 s, its implicit velocity update
# solved to Simbody's default of 1e-3 and to 1e-9. Loosely solved the step is no longer time-reversible, and K's
# largest change grows past its bounded 4.2e-6 (to 9.9e-6 by 100 s); solved to 1e-9 it stays there.
k_change() { sed -n 's/^Largest relative change over the run: K \([0-9.e+-]*\),.*/\1/p' "$1"; }
for accuracy in 1e-3 1e-9; do
  run_capture "verlet$accuracy" "$BIN_DIR/book-reference" --spin intermediate --integrator Verlet --fixed-step \
    --dt 0.001 --final-time 100 --accuracy "$accuracy" --quiet --output "verlet$accuracy.txt"
done
loose=$(k_change verlet1e-3.out) tight=$(k_change verlet1e-9.out)
check "over 100 s Verlet's K changes twice as much solved to 1e-3 ($loose) as solved to 1e-9 ($tight), under 5e-6" \
  awk -v a="$loose" -v b="$tight" 'BEGIN { exit !(a != "" && b != "" && a >= 2 * b && b < 5e-6) }'

# A student's own book file, followed the same way: built and run in grading's sandbox, its CSV read as data and
# its figure drawn by simlab. The solution's file gives the reference's table, figure for figure.
cp "$SOURCE_DIR/solutions/book/BookSpin.cpp" .
run_capture own "$SIMLAB" study long-run book --quick -o own --file BookSpin.cpp
check "simlab study long-run book --file ends well" test "$(status_of own)" -eq 0
check "  with the reference solution's table, setting for setting" \
  bash -c "diff <(grep -E '^  (RungeKuttaMerson|Verlet),' book.out | sed 's/ *[0-9.]*\$//') \
                <(grep -E '^  (RungeKuttaMerson|Verlet),' own.out | sed 's/ *[0-9.]*\$//')"
check "  its CSV, with the samples of the reference's" \
  bash -c "diff <(cut -d, -f1-3,5- view/book-long-run.csv) <(cut -d, -f1-3,5- own/book-long-run.csv)"
if command -v gnuplot >/dev/null; then
  check "  and its figure, drawn from the CSV, a curve per setting" \
    bash -c "grep -q '<svg' own/book-long-run.svg && grep -q 'Verlet, fixed step 0.001 s' own/book-long-run.svg"
fi
check "  and where they are, named as the output folder (not the sandbox's)" grep -q "^Written to $PWD/own: book-long-run.csv" own.out
run_capture own_boot "$SIMLAB" study long-run biosim --quick --file BookSpin.cpp
check "--file with the boot's view is refused in one line, exit 2" \
  bash -c "test $(status_of own_boot) -eq 2 && test \$(wc -l <own_boot.err) -eq 1 && grep -q \"biosim's long-run view is its worked example's\" own_boot.err"

run_capture banana "$SIMLAB" study long-run apple --quick
check "a lab without the view is refused in one line, exit 2" \
  bash -c "test $(status_of banana) -eq 2 && test \$(wc -l <banana.err) -eq 1 && grep -q 'book or biosim' banana.err"
run_capture zero "$SIMLAB" study long-run book --final-time 0
check "a final time out of range is refused in one line, exit 2" \
  bash -c "test $(status_of zero) -eq 2 && test \$(wc -l <zero.err) -eq 1 && grep -q 'final-time' zero.err"
finish
