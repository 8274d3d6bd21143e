# simlab study trade: every integrator at every accuracy and fixed step, none missing, each under its cap; the
# figures hold the physics (constant acceleration is integrated exactly by second-order methods, Euler is first
# order); plots and the table are made; a student's file is studied in the sandbox, as data; an unknown lab is a
# one-line error. The studies the handouts run (the apple's and the boot's quick and minimal studies) are read from
# their handouts' runs ($FIXTURES/handouts/<lab>), not run again.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

# The apple's quick study, as its handout runs it on a finished file (handouts/apple, which compares the table it
# prints): kept in $FIXTURES/handouts/apple.
handout=$FIXTURES/handouts/apple/solution-tree
st=$handout/study
check "simlab study trade apple --quick (the handout's run) wrote trade.csv" test -s "$st/trade.csv"
check "trade.csv has a row for each of 9 integrators x 14 accuracies and 8 methods x 4 fixed steps" \
  test "$(tail -n +2 "$st/trade.csv" | wc -l)" -eq 158
check "every row has a named status" \
  bash -c "! tail -n +2 '$st/trade.csv' | cut -d, -f7 | grep -vxE 'ok|too costly|failed|blew up|no error control'"
field() {  # field INTEGRATOR MODE SETTING COLUMN: one figure of trade.csv's apple rows
  awk -F, -v i="$1" -v m="$2" -v s="$3" -v c="$4" \
    '$2 == "apple" && $3 == i && $4 == m && ($5 + 0 == s + 0 || $6 + 0 == s + 0) { print $c }' "$st/trade.csv"
}
check "Verlet integrates the apple's constant acceleration exactly (15 digits or more at accuracy 1e-4)" \
  awk "BEGIN { exit !($(field Verlet accuracy 1e-4 10) >= 15) }"
check "explicit Euler at a fixed step of 0.4 s is first order: under 2 digits" \
  awk "BEGIN { exit !($(field ExplicitEuler 'fixed step' 0.4 10) < 2) }"
check "ten times the steps buys explicit Euler one digit (0.4 s to 0.04 s)" \
  awk "BEGIN { d = $(field ExplicitEuler 'fixed step' 0.04 10) - $(field ExplicitEuler 'fixed step' 0.4 10); exit !(d > 0.8 && d < 1.2) }"
apple_study=$handout/simlab-study-trade-apple-quick-no-plots-o-study-file-starter-apple-NewtonsApple-cpp.out
check "the table gives the cheapest setting for 4 to 12 digits" \
  bash -c "grep -q 'cheapest setting' $apple_study && test \$(grep -cE '^  (4|6|8|10|12) ' $apple_study) -eq 5"
# The table marks what a front cannot promise (read from the handouts' runs): a method whose digits fall back below
# a target as it tightens (on the book's question spin CPodes keeps 8.1 digits at 1e-11 and 7.9 at 1e-12), with the
# cheapest setting of a steadier one; the stretches of digits no setting keeps; and the projectile's ground hit,
# the lab's other figure, in a table and front of its own.
bq=$FIXTURES/handouts/book/solution-tree/simlab-study-trade-book-question-quick-no-plots-o-question-file-starter-book-BookSpin-cpp.out
check "a question's table gives the digits it asks and each one its grader reads past them: 8, 9 and 10" \
  bash -c "test \"\$(grep -oE '^  (8|9|10) ' '$bq' | tr -d ' ' | tr '\n' ' ')\" = '8 9 10 '"
check "a method not monotone about a target is marked, with a steadier method's cheapest setting" \
  bash -c "grep -q \"^  8       CPodes, accuracy 1e-11 .* \\*\$\" '$bq' &&
           grep -q \"CPodes's digits are not monotone in its setting (accuracy 1e-11 keeps 8.1, accuracy 1e-12 keeps 7.9)\" '$bq' &&
           grep -q '(cheapest whose method gains digits steadily)' '$bq'"
check "the stretches of a front no setting measured reaches are named" \
  grep -q 'no setting measured keeps 6.3 to 8.0 digits' "$bq"
pq=$FIXTURES/handouts/projectile/solution-tree/simlab-study-trade-projectile-quick-no-plots-o-study-file-starter-projectile-ProjectileMotion-cpp.out
check "the projectile's ground hit has its own table: Verlet at 1e-1 keeps 15.5 digits of the flight, 10.2 of the hit" \
  bash -c "grep -q '^  At the end of the run, the ground hit' '$pq' &&
           test \$(grep -cE '^  4       Verlet, accuracy 1e-01 +29 +(15.5|10.2) ' '$pq') -eq 2"

if command -v gnuplot >/dev/null; then
  # Drawn from any study: a small one (points past 2000 evaluations too costly) is enough to draw.
  run_capture plots "$SIMLAB" study trade apple --quick --max-evaluations 2000 -o plotted
  check "digits against evaluations and against time, as PNG and SVG" \
    test -s plotted/apple-evaluations.png -a -s plotted/apple-evaluations.svg -a -s plotted/apple-time.png -a -s plotted/apple-time.svg
fi

run_capture reference "$SIMLAB" study trade apple --quick --no-plots -o fs
check "--file studies a student's file: the solution's copy (the handout's run) gives the reference's table" \
  bash -c "test $(status_of reference) -eq 0 && diff <(cut -d, -f1-15 '$st/trade.csv') <(cut -d, -f1-15 fs/trade.csv) >/dev/null"
run_capture starter "$SIMLAB" study trade apple --quick --no-plots --file "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" -o fs2
check "and an unfinished file stops the study, naming its first TODO" \
  bash -c "test $(status_of starter) -ne 0 && grep -q 'not done yet (NewtonsApple.cpp:' starter.err"
# A student's file is built with grading's object check and run in grading's sandbox: a constructor that would run
# before the course's code is refused, and code that reads what grading keeps from it finds nothing.
sed 's|^namespace apple {|static volatile int early;\n__attribute__((constructor(101))) static void first() { early = 1; }\nnamespace apple {|' \
  "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" >Prioritized.cpp
run_capture prioritized "$SIMLAB" study trade apple --quick --no-plots --file Prioritized.cpp -o fs3
check "--file refuses what grading refuses (a prioritized constructor), exit 2" \
  bash -c "test $(status_of prioritized) -eq 2 && grep -q 'is refused (forbidden code)' prioritized.err && \
           grep -q 'constructor with a priority' prioritized.err"
{ cat "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp"
  printf '%s\n' '#include <fstream>' \
    'static const bool readIt = [] { std::ifstream in("'"$SOURCE_DIR"'/assignments/apple/grading/hidden.cpp");' \
    '  if (in) throw std::runtime_error("read the hidden tests"); return true; }();'
} >Reader.cpp
run_capture reader "$SIMLAB" study trade apple --quick --max-evaluations 2000 --no-plots --file Reader.cpp -o fs4
check "and runs it in the sandbox, where the hidden tests cannot be read: the study completes" \
  bash -c "test $(status_of reader) -eq 0 && grep -q 'cheapest setting' reader.out"

# What a student's study program prints is data: a line no study prints - a scene named with a newline and gnuplot's
# commands after it, which would run a shell as simlab's user - stops the study in one line, and reaches no tool.
{ cat "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp"
  printf '%s\n' '#include <cstdio>' \
    'static const bool forged = [] { std::fputs("{\"type\": \"subject\", \"lab\": \"apple\", \"subject\": \"x\\nsystem(\\\"touch PWNED\\\")\\n#\", \"figure\": \"f\", \"reference\": \"r\", \"final_time\": 1}\n", stdout); return true; }();'
} >Forged.cpp
run_capture forged "$SIMLAB" study trade apple --quick --max-evaluations 2000 --file Forged.cpp -o fs5
check "a forged line stops the study of a student's file, in one line, and no command of it runs" \
  bash -c "test $(status_of forged) -eq 1 && grep -q 'printed a line no study prints (a subject named' forged.err &&
           test \$(grep -c 'simlab: error' forged.err) -eq 1 && test -z \"\$(find . -name PWNED)\""

# The boot's quick study and its minimal study, as its handout runs them (handouts/biosim, which compares what they
# print, the reference's accuracy of 13.5 digits among it): kept in $FIXTURES/handouts/biosim.
boot=$FIXTURES/handouts/biosim/solution-tree/study
check "CPodes at accuracy 1e-10 keeps 4 digits or more of the chaotic boot over 5 s" \
  awk -F, '$3 == "CPodes" && $4 == "accuracy" && $5 + 0 == 1e-10 { found = 1; ok = $10 >= 4 } END { exit !(found && ok) }' \
  "$boot/trade.csv"

run_capture minimal "$SIMLAB" study minimal book --repeats 1 -o min
check "simlab study minimal book measures each spin's curve on its Ball (3 dof) and on a Free mobilizer (6 dof)" \
  bash -c "test $(status_of minimal) -eq 0 && test \$(grep -c ',Ball (3 dof),no,3,4,RungeKuttaMerson,[0-9.e-]*,ok,' min/minimal-points.csv) -eq 69 && \
           test \$(grep -c ',Free (6 dof),yes,6,7,RungeKuttaMerson,[0-9.e-]*,ok,' min/minimal-points.csv) -eq 69"
check "and compares them at equal digits, read along both curves, from 1 to 9 digits or more for each spin" \
  awk -F, 'NR > 1 && $5 == "along both curves" { n[$2]++; if ($4 > top[$2]) top[$2] = $4; if ($4 < 1) low = 1 }
           END { exit !(n["book-min"] >= 3 && n["book-intermediate"] >= 3 && n["book-max"] >= 3 && !low &&
                        top["book-min"] >= 9 && top["book-intermediate"] >= 9 && top["book-max"] >= 9) }' min/minimal.csv
check "where the spin costs the Ball and the Free book the same evaluations, within 10 %" \
  awk -F, 'NR > 1 { n++; if ($10 < 0.9 || $10 > 1.1) bad = 1 } END { exit !(n >= 9 && !bad) }' min/minimal.csv
check "and each row's cost is the over-modelled one over the minimal one, in evaluations and in time" \
  awk -F, 'NR > 1 { n++; r = $8 / $6; t = $9 / $7; if (r / $10 < 0.999 || r / $10 > 1.001 || t / $11 < 0.999 || t / $11 > 1.001) bad = 1 }
           END { exit !(n >= 9 && !bad) }' min/minimal.csv
check "the table says how the costs were read and timed" \
  bash -c "grep -q 'at equal digits' minimal.out && grep -q 'read along its own curve of 23 accuracies' minimal.out && \
           grep -q 'fastest of alternating batches of runs at least' minimal.out"

check "the over-modelled boot (a Free rod held by 5 constraints) has the boot's 2 dof in 8 coordinates" \
  bash -c "test \$(grep -c ',two Pins (2 dof),no,2,2,' '$boot/minimal-points.csv') -eq 23 && \
           test \$(grep -c ',Free + 5 constraints,yes,2,8,RungeKuttaMerson,[0-9.e-]*,ok,' '$boot/minimal-points.csv') -ge 20"
check "and is compared with the two Pins at equal digits, three digits or more apart" \
  awk -F, 'NR > 1 && $5 == "along both curves" { n++; if (!lo || $4 < lo) lo = $4; if ($4 > hi) hi = $4 }
           END { exit !(n >= 3 && hi - lo >= 3) }' "$boot/minimal.csv"
check "the apple, which every accuracy follows exactly, is compared at the digits both models keep at their loosest" \
  bash -c "test \$(grep -c ',at a loosest accuracy,26,[0-9.e-]*,26,' '$st/minimal.csv') -eq 1 && \
           grep -q 'the loosest accuracy already keeps these digits' $handout/simlab-study-minimal-apple-repeats-1-o-study-file-starter-apple-NewtonsApple-cpp.out"

# The extremes, without the slow cases (each of those runs into its cap): every outcome named, every promise kept.
for lab in apple projectile book biosim; do
  run_capture "extremes-$lab" "$SIMLAB" study extremes "$lab" --quick -o "ex-$lab"
  check "simlab study extremes $lab --quick: every case ends named, as the lab promises" \
    bash -c "test $(status_of "extremes-$lab") -eq 0 && ! grep -q SILENT ex-$lab/extremes.csv"
  least=40
  [[ $lab == biosim ]] && least=45
  check "and $lab has $least extreme cases or more" \
    test "$(grep -c '^\[\[case\]\]' "$SOURCE_DIR/assignments/$lab/study/extremes.toml")" -ge $least
done
# Each extreme case named below ends as its check says, in the study's extremes.csv.
outcome() {  # outcome DESCRIPTION LAB PATTERN (an extended regular expression over extremes.csv)
  check "$1" grep -qE "$3" "ex-$2/extremes.csv"
}
outcome "a cube's spin is right to 14 digits (its exact w is constant, not zero)" book \
  '^book,a cube,.*,accurate,1[4-5]\.[0-9],'
outcome "a flight shorter than one fixed step says it cannot see the ground hit" projectile \
  'fixed steps,.*trouble,.*No ground hit'
outcome "an integrator whose steps cannot advance time says so, not Simbody's words" book \
  '^book,RungeKutta3 at accuracy 1e-15.*the integrator could not advance past t = '
outcome "a flight whose size a double's square cannot hold is refused for that, before Simbody asserts" projectile \
  '^projectile,a speed of 1e80 m/s.*rejected,.*whose square Simbody'
outcome "CPodes at fixed steps is refused before it runs, saying it has none" apple \
  '^apple,CPodes at fixed steps.*rejected,.*CPodes takes no fixed steps'
outcome "SemiExplicitEuler at steps too coarse for the flight lands where its steps do, its digits said" \
  projectile '^projectile,"?SemiExplicitEuler at 2 s steps.*inaccurate,0\.3,.*exact 33\.1693858347622 m: 0\.6 accurate digits'
outcome "the boot with no gravity and no motion stays exactly at rest, and says so" biosim \
  'no gravity,.*accurate,15.7,.*At rest, as the exact solution is'
outcome "a value --set does not allow is a usage error (exit 2), like any option's" biosim \
  'gravity past its range,.*rejected,.*outside its range'
outcome "explicit Euler's blow-up of the book's energy is named where it broke" book \
  'for 20 s.*trouble,.*the run broke at t = '
outcome "a flight Simbody's event handling cannot follow is refused, and the reason is the flight's length" projectile \
  'gravity 1e-300 .*rejected,,.*the flight lasts 5.13e\+301 s'
outcome "so is a flight shorter than Simbody can time, never blamed on the student's event handler" projectile \
  'a speed of 1e-300 .*rejected,,.*Simbody times events to about 1.8e-14 s'
outcome "a book of 1e-300 kg is refused for its mass, not for a step Simbody could not take" book \
  'a mass of 1e-300 kg,.*rejected,,.*outside 1e-100 to 1e100 kg'
outcome "a spin of 1e-100 rad/s has its relative changes, not NaN (magnitudes without squares)" book \
  'wobbling.*,accurate,15.7,'
outcome "a run that finishes with fewer than 3 digits is called inaccurate" book \
  'fixed steps of 0.1 s.*inaccurate,0.0,'

run_capture unknown "$SIMLAB" study trade nosuch
check "an unknown lab is a one-line error and exit 2" \
  bash -c "test $(status_of unknown) -eq 2 && test \$(wc -l <unknown.err) -eq 1"
finish
