# The projectile lab program, headless: the reference's trajectory and ground hit are accurate, a 20-degree
# launch at 25 m/s too, the starter stops at its first SIMLAB_TODO, the trade table runs, the plot is drawn.
# shellcheck source=lib.sh
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

# A flight shorter than one sampling interval still lands where it should.
for launch in "--angle 0.001" "--speed 1e-6"; do
  run_capture short "$projectile" $launch --quiet --output short.txt
  digits=$(sed -n 's/.*exact t\*.*: \([0-9.]*\) accurate digits/\1/p' short.out)
  check "a flight shorter than dt ($launch) finds its ground hit to 7+ digits of t* (${digits:-none})" \
    awk "BEGIN { exit !(\"$digits\" != \"\" && $digits >= 7) }"
done
run_capture short_fixed "$projectile" --angle 0.001 --fixed-step --quiet --output short.txt
check "at fixed steps longer than the flight it says so and what to do" \
  grep -q '^No ground hit: .*: the flight lasts t\* = 0.000159 s, too short for fixed steps of --dt 0.01 s.*use --dt' short_fixed.out

# A flight of 5e10 s under g = 1e-9 is followed to its end.
run_capture weak "$projectile" --gravity 1e-9 --quiet --output weak.txt
check "under g = 1e-9 the ground hit is at t* = 5.1278e10 s" grep -q 'Ground hit .*: t = 5127773340[0-9.]* s' weak.out

# Values whose exact value is zero are counted against the distance flown, and the line says so.
run_capture vertical "$projectile" --angle 90 --quiet --output vertical.txt
digits=$(sed -n 's/^x(.*: \([0-9.]*\) accurate digits (of v0 t = 233.781 m)/\1/p' vertical.out)
check "x of a vertical launch (exact 0) to 13+ digits of v0 t (${digits:-none})" awk "BEGIN { exit !(\"$digits\" != \"\" && $digits >= 13) }"
run_capture long "$projectile" --final-time 1e4 --quiet --output long.txt
digits=$(sed -n 's/^y(.*: \([0-9.]*\) accurate digits (of v0 t = .* m)/\1/p' long.out)
check "y at the ground hit (exact 0) to 13+ digits of v0 t (${digits:-none})" awk "BEGIN { exit !(\"$digits\" != \"\" && $digits >= 13) }"
check "and the table's early end is said" grep -q '^The table ends at t = 5.2324217765[0-9]* s, before the final time 10000 s' long.out

run_capture starter "$BIN_DIR/projectile"
check "the starter program stops with status 3 at its first TODO" \
  bash -c "test $(status_of starter) -eq 3 && grep -q 'not done yet (ProjectileMotion.cpp:' starter.err"

run_capture trade "$projectile" --trade --dt 0.5
check "the trade table has a row per accuracy and window (20)" test "$(grep -cE '^ +[0-9.e-]+ +[0-9.e-]+ +[0-9.]+ +[0-9.]+ +[0-9]+ ' trade.out)" -eq 20

if command -v gnuplot >/dev/null; then
  run_capture plot gnuplot -e "out='projectile.png'" "$SOURCE_DIR/handouts/plots/projectile.gp"
  check "the handout's gnuplot script plots y(x)" test -s projectile.png -a "$(status_of plot)" -eq 0
fi
# Near vertical, x* is near zero: its digits are of v0 t*, and the line says so; the banner keeps the angle's digits.
run_capture vertical "$projectile" --angle 89.9999999 --quiet --output vertical.txt
check "a launch a tenth of a microdegree short of vertical states the scale of x*'s digits" \
  grep -qE 'exact x\* .*accurate digits of v0 t\* = 407\.773 m \(x\* is near 0\)' vertical.out
check "and its banner shows the angle as given, not rounded to 90" grep -q '89\.9999999 degrees' vertical.out
check "at 35 degrees x*'s digits are its own" grep -qE 'exact x\* .*: [0-9.]+ accurate digits$' default.out
# The table and the hit are one run where its event ends the table: at fixed steps of 2 s, too coarse for a run on to
# the ground, the table's own run landed, and that is the hit reported.
run_capture coarse "$projectile" --fixed-step --dt 2 --final-time 10 --quiet --output coarse.txt
check "at fixed steps of 2 s the hit is the table's own run's, never 'No ground hit' beside it" \
  bash -c "grep -q 'Ground hit .*(RungeKuttaMerson, 3 steps: the run above)' coarse.out && ! grep -q 'No ground hit' coarse.out"
# A tiny energy (a ball at 1e-8 m/s) whose terms cancel is no blow-up: the run ends with its ground hit.
run_capture slow "$projectile" --speed 1e-8 --quiet --output slow.txt
check "a ball at 1e-8 m/s runs to its ground hit (its energy's rounding is not growth)" \
  bash -c "test $(status_of slow) -eq 0 && grep -q 'Ground hit' slow.out"

finish
