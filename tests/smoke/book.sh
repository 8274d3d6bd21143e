# The book lab program, headless: every spin's w(4) matches the elliptic solution to 8 digits at the default
# accuracy, the intermediate spin's wobble grows at the linear rate, options are checked, the starter stops at its
# first SIMLAB_TODO, the trade table runs, the plot is drawn.
source "$(dirname "$0")/lib.sh"
book="$BIN_DIR/book-reference"

for spin in min intermediate max; do
  run_capture $spin "$book" --spin $spin --quiet --output $spin.txt
  digits=$(sed -n 's/.*elliptic functions): \([0-9.]*\) accurate digits.*/\1/p' $spin.out)
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

run_capture starter "$BIN_DIR/book"
check "the starter program stops with status 3 at its first TODO" \
  bash -c "test $(status_of starter) -eq 3 && grep -q 'not done yet (BookSpin.cpp:' starter.err"

run_capture trade "$book" --trade --final-time 0.5
check "the trade table lists all nine integrators" test "$(grep -cE '^(RungeKutta|ExplicitEuler|SemiExplicit|Verlet|CPodes)' trade.out)" -eq 9

if command -v gnuplot >/dev/null; then
  run_capture plot gnuplot -e "results='intermediate.txt'; out='book.png'" "$SOURCE_DIR/handouts/plots/book.gp"
  check "the handout's gnuplot script plots w, K and |H|" test -s book.png -a "$(status_of plot)" -eq 0
fi
finish
