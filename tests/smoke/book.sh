# The book lab program, headless: every spin's w(4) matches the elliptic solution to 8 digits at the default
# accuracy, the intermediate spin's wobble grows at the linear rate, options are checked, the starter stops at its
# first SIMLAB_TODO, the trade table runs, the plot is drawn.
# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
book="$BIN_DIR/book-reference"

for spin in min intermediate max; do
  run_capture $spin "$book" --spin $spin --quiet --output $spin.txt
  digits=$(sed -n 's/.*(elliptic functions, certified by [^)]*): \([0-9.]*\) accurate digits.*/\1/p' $spin.out)
  check "spin about the $spin axis: w(4) to 8+ digits of the elliptic solution ($digits)" awk "BEGIN { exit !($digits >= 8) }"
done
check "the results file has the lab's columns" test "$(head -n 1 min.txt)" = \
  "$(printf 'time\twx\twy\twz\tHx\tHy\tHz\tHmag\tK\tHGx\tHGy\tHGz')"
check "a row for t = 0, 0.01, ..., 4" test "$(($(wc -l <min.txt) - 1))" -eq 401
ratio=$(sed -n 's/.*measured \/ linear = \([0-9.]*\)).*/\1/p' intermediate.out)
check "the wobble about the intermediate axis grows at the linear rate, 4.08 rad/s (measured / linear = $ratio)" \
  awk "BEGIN { exit !($ratio > 0.95 && $ratio < 1.05) }"
check "and only that spin reports a growth rate" bash -c "! grep -q 'grows at' min.out max.out"

run_capture omega "$book" --omega -1.3,2.1,-0.7 --dimensions 0.25,0.17,0.03 --mass 1.2 --quiet --output omega.txt
check "--omega, --dimensions and --mass run" grep -q 'w0 = (-1.3, 2.1, -0.7)' omega.out

# A cube's w never changes; an axisymmetric book's precesses about its symmetry axis: the exact solution follows both.
run_capture cube "$book" --dimensions 0.1,0.1,0.1 --omega 1,2,3 --quiet --output cube.txt
digits=$(sed -n 's/.*(elliptic functions, certified by [^)]*): \([0-9.]*\) accurate digits.*/\1/p' cube.out)
check "a cube keeps w = (1, 2, 3): 14+ digits of the exact solution ($digits)" \
  bash -c "grep -q 'exact   (1, 2, 3) rad/s' cube.out && awk 'BEGIN { exit !($digits >= 14) }'"
run_capture axisymmetric "$book" --dimensions 0.2,0.2,0.05 --omega 1,2,3 --quiet --output axisymmetric.txt
check "an axisymmetric book's exact w agrees with Euler's equations integrated in long double and in 113-bit floats" \
  grep -q '(elliptic functions, certified by [^)]*113-bit floats): [0-9.]* accurate digits' axisymmetric.out

# The wobble's growth rate is given only where it is meaningful, never negative, nan or inf.
run_capture fast "$book" --omega 1000,0.2,0.2 --quiet --output fast.txt
run_capture still "$book" --omega 7,0,0 --quiet --output still.txt
run_capture nearly "$book" --dimensions 0.2,0.2001,0.05 --spin intermediate --quiet --output nearly.txt
for run in fast still nearly; do
  check "no growth rate for $run, and one line saying why" \
    bash -c "! grep -q 'grows at' $run.out && test \$(grep -c '^No growth rate: ' $run.out) -eq 1 && ! grep -qi 'nan\|inf' $run.out"
done

# The digits reported are no more than the reference integration of Euler's equations can confirm.
run_capture tight "$book" --spin intermediate --accuracy 1e-14 --quiet --output tight.txt
digits=$(sed -n 's/.*): \([0-9.]*\) accurate digits.*/\1/p' tight.out)
check "the intermediate spin at accuracy 1e-14 is right to 13.1 digits, not 13.7 ($digits)" \
  awk "BEGIN { exit !($digits >= 12.8 && $digits <= 13.4) }"
digits=$(sed -n 's/.*): \([0-9.]*\) accurate digits.*/\1/p' fast.out)
check "at 1000 rad/s the exact w comes from the long double integration ($digits digits)" \
  bash -c "grep -q 'the elliptic functions hold 7\.[0-9] digits here' fast.out && awk 'BEGIN { exit !($digits < 3) }'"

# A run that blows up stops at the first bad row, says where in one line, and leaves no inf or nan in its file.
run_capture euler "$book" --integrator ExplicitEuler --fixed-step --dt 0.5 --spin max --final-time 20 --quiet --output euler.txt
check "Euler's blow-up is a failure (status $(status_of euler)) named in one line" \
  bash -c "test $(status_of euler) -ne 0 && test \$(wc -l <euler.err) -eq 1 && grep -q 'error: the run broke at t = 3.5 s: K moved from' euler.err"
check "and its results file keeps the finite rows, then says where it broke" \
  bash -c "! grep -qi 'inf\|nan' <(grep -v '^#' euler.txt) && tail -n 1 euler.txt | grep -q '^# the run broke at t = 3.5 s'"

# CPodes' own messages stay off the screen: a failure is one line. (At its tightest accuracy CPodes gives up on the
# intermediate spin within 20 s, wherever its steps put the failure: 4 s is too short to be sure of one.)
run_capture cpodes "$book" --integrator CPodes --accuracy 1e-15 --spin intermediate --final-time 20 --quiet \
  --output cpodes.txt
check "a CPodes failure is one line on stderr that names its cause, not Simbody's words ($(wc -l <cpodes.err) lines)" \
  bash -c "test $(status_of cpodes) -eq 1 && test \$(wc -l <cpodes.err) -eq 1 && grep -q '^book: error: CPodes gave up at t = [0-9.e+-]* s: no step it can take there meets the accuracy' cpodes.err"

run_capture starter "$BIN_DIR/book"
check "the starter program stops with status 3 at its first TODO" \
  bash -c "test $(status_of starter) -eq 3 && grep -q 'not done yet (BookSpin.cpp:' starter.err"

# One run a row: the rows are what is checked here (a median of five took 18 s against 3.6).
run_capture trade "$book" --trade --final-time 0.5 --repeats 1
check "the trade table lists all nine integrators" test "$(grep -cE '^(RungeKutta|ExplicitEuler|SemiExplicit|Verlet|CPodes)' trade.out)" -eq 9

if command -v gnuplot >/dev/null; then
  run_capture plot gnuplot -e "results='intermediate.txt'; out='book.png'" "$SOURCE_DIR/handouts/plots/book.gp"
  check "the handout's gnuplot script plots w, K and |H|" test -s book.png -a "$(status_of plot)" -eq 0
fi
finish
