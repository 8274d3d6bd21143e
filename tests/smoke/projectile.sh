# The projectile lab program, headless: the reference's trajectory and ground hit are accurate, a 20-degree
# launch at 25 m/s too, the starter stops at its first SIMLAB_TODO, the trade table runs, the plot is drawn.
source "$(dirname "$0")/lib.sh"
projectile="$BIN_DIR/projectile-reference"

run_capture default "$projectile" --quiet
check "the reference program succeeds" test "$(status_of default)" -eq 0
check "the results file has the lab's columns" test "$(head -n 1 ProjectileMotionResults.txt)" = \
  "$(printf 'time\tx\ty\txVelocity\tyVelocity\tmechanicalEnergy\tyDifferenceFromExact')"
check "a row for t = 0, 0.01, ..., 5.23" test "$(($(wc -l <ProjectileMotionResults.txt) - 1))" -eq 524
check "the ground hit is at t = 5.232422 s" grep -q 'Ground hit .*: t = 5\.232421776' default.out
check "and x = 191.5909 m" grep -q 'x = 191\.59086006' default.out
digits() { sed -n "s/.*exact $1.*: \([0-9.]*\) accurate digits/\1/p" default.out; }
check "both to at least 7 digits ($(digits 't\*'), $(digits 'x\*'))" \
  awk "BEGIN { exit !($(digits 't\*') >= 7 && $(digits 'x\*') >= 7) }"

run_capture variant "$projectile" --angle 20 --speed 25 --quiet --output variant.txt
check "a 20-degree launch at 25 m/s lands at t* = 2 (25 sin 20)/9.8 = 1.745 s" grep -q 't\* = 2 v0 sin(theta)/g = 1\.7450' variant.out

run_capture starter "$BIN_DIR/projectile"
check "the starter program stops with status 3 at its first TODO" \
  bash -c "test $(status_of starter) -eq 3 && grep -q 'not done yet (ProjectileMotion.cpp:' starter.err"

run_capture trade "$projectile" --trade --dt 0.5
check "the trade table has a row per accuracy and window (20)" test "$(grep -cE '^ +[0-9.e-]+ +[0-9.e-]+ +[0-9.]+ +[0-9.]+ +[0-9]+ ' trade.out)" -eq 20

if command -v gnuplot >/dev/null; then
  run_capture plot gnuplot -e "out='projectile.png'" "$SOURCE_DIR/handouts/plots/projectile.gp"
  check "the handout's gnuplot script plots y(x)" test -s projectile.png -a "$(status_of plot)" -eq 0
fi
finish
