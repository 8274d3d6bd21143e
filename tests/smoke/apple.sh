# The apple lab program, headless: the reference runs and is accurate, Euler is visibly less accurate,
# the starter stops at its first SIMLAB_TODO, the trade table lists every integrator.
# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
apple="$BIN_DIR/apple-reference"

digits_of() { sed -n 's/.*: \([0-9.]*\) accurate digits.*/\1/p' "$1"; }
last_difference() { tail -n 1 "$1" | awk -F'\t' '{ d = $5 < 0 ? -$5 : $5; print d }'; }

run_capture default "$apple" --quiet --output default.txt
check "the reference program succeeds" test "$(status_of default)" -eq 0
check "the results file has the handout's columns" \
  test "$(head -n 1 default.txt)" = "$(printf 'time\tyLocation\tyVelocity\tmechanicalEnergy\tyDifferenceFromExact')"
check "the results file has a row for t = 0, 0.01, ..., 4" test "$(($(wc -l <default.txt) - 1))" -eq 401
check "values are written at full double precision" grep -q -- '-68.400000000000' default.txt
default_digits=$(digits_of default.out)
check "RungeKuttaMerson reaches 13+ digits of y(4) (got $default_digits)" awk "BEGIN { exit !($default_digits >= 13) }"

run_capture euler "$apple" --integrator ExplicitEuler --dt 0.01 --quiet --output euler.txt
euler_digits=$(digits_of euler.out)
check "ExplicitEuler reports fewer digits ($euler_digits) than the default ($default_digits)" \
  awk "BEGIN { exit !($euler_digits < $default_digits - 5) }"
check "and its larger error shows in the last column of the results file" \
  awk "BEGIN { exit !($(last_difference euler.txt) > 1000 * $(last_difference default.txt) + 1e-6) }"

run_capture starter "$BIN_DIR/apple"
check "the starter program stops with status 3" test "$(status_of starter)" -eq 3
check "and says which SIMLAB_TODO is not done" grep -q 'not done yet (NewtonsApple.cpp:[0-9]*): build the model' starter.err

run_capture trade "$apple" --trade --final-time 0.5
check "the trade table runs" test "$(status_of trade)" -eq 0
check "and lists all nine integrators" test "$(grep -cE '^(RungeKutta|ExplicitEuler|SemiExplicit|Verlet|CPodes)' trade.out)" -eq 9

if command -v gnuplot >/dev/null; then
  run_capture plot gnuplot -e "results='default.txt'; out='apple.png'" "$SOURCE_DIR/handouts/plots/apple.gp"
  check "the handout's gnuplot script plots the results file" test -s apple.png -a "$(status_of plot)" -eq 0
fi

if command -v xvfb-run >/dev/null; then
  run_capture animate timeout 120 xvfb-run -a "$apple" --animate --final-time 0.3 --quiet --output animate.txt
  check "--animate plays the fall in Simbody's visualizer on an off-screen display" test "$(status_of animate)" -eq 0
fi
DISPLAY='' run_capture no_display "$apple" --animate --quiet --output no-display.txt
check "--animate without a display is a one-line error" grep -q 'needs a display' no_display.err

run_capture help "$apple" --help
check "--help works" test "$(status_of help)" -eq 0
# An energy whose terms cancel: the fall's kinetic and potential energies reach 1e19 J and sum to 1.4e4 J, so
# rounding alone moves each row's energy by about 2.2e-16 of 1.42e19 J, 3.1e3 J, and its change over the run (8.9e2 J)
# is of that order, which the run says; the default run says nothing of it.
run_capture cancel "$apple" --final-time 1e6 --gravity 1e4 --dt 1e4 --quiet --output cancel.txt
check "a fall whose energy terms cancel to 1e-15 of their size says how far rounding moves the energy" \
  grep -qE "Note: mechanicalEnergy sums terms of up to 1\.42e\+19 that cancel, so rounding moves each row's value by about 3\.1e\+03 .* is of that rounding's order" cancel.out
check "the lab's fall says nothing of rounding" bash -c "! grep -q 'rounding moves' default.out"

finish
