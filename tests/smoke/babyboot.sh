# The baby boot and the project template, headless: the boot's results file has the columns the handout names, it
# conserves energy to the accuracy asked for, --set changes the run and refuses unknown or out-of-range names in
# one line, --schematic draws the tree and the model at t = 0, the trade table runs; the template stops at its first
# SIMLAB_TODO; `simlab project new` makes a project that builds with CMake and runs.
# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
boot="$BIN_DIR/babyboot"

run_capture default "$boot" --quiet --output boot.txt
check "the boot runs at its defaults" test "$(status_of default)" -eq 0
check "the results file has the columns time, qA, qB, uA, uB, energy" test "$(head -n 1 boot.txt)" = \
  "$(printf 'time\tqA\tqB\tuA\tuB\tenergy')"
check "a row for t = 0, 0.01, ..., 10" test "$(($(wc -l <boot.txt) - 1))" -eq 1001
# The energy starts at zero (the rod horizontal, at rest); the swing exchanges g (mA LA + mB LB) = 0.2 J.
check "the energy stays within 1e-7 J of zero" awk -F'\t' 'NR > 1 && ($6 > 1e-7 || $6 < -1e-7) { bad = 1 } END { exit bad }' boot.txt

# Balanced 1.7e-9 rad from upright, the boot's fall is fixed by the last digits of its start: --trade says how many
# digits of q and u the parameters themselves fix.
run_capture upright "$boot" --trade --repeats 1 --final-time 5 --set qA=179.9999999 --set uA=0 --set uB=0
check "near upright, --trade says how few digits the parameters fix" \
  bash -c "test $(status_of upright) -eq 0 && grep -qE '^Conditioning: a unit in the last place of each parameter changes q and u at t = 5 s to ([0-9]|1[01])\.[0-9] digits' upright.out"

# A replay watches the run at its own frame times; the figures the program prints must not depend on it.
run_capture replayed "$boot" --quiet --output replayed.txt --replay replayed.html
check "with --replay the results and the energy line are those of the run without it" \
  bash -c "cmp -s boot.txt replayed.txt && test \"\$(grep '^Energy' default.out)\" = \"\$(grep '^Energy' replayed.out)\""

run_capture still "$boot" --quiet --set g=0 --set uA=0 --set uB=0 --output still.txt
check "--set g=0 with no initial rates: the boot stays at rest" \
  awk -F'\t' 'NR > 1 && ($2 != 90 || $3 != 1) { moved = 1 } END { exit moved }' still.txt
run_capture typo "$boot" --set qa=10
check "a misspelt parameter is a one-line error" \
  bash -c "test $(status_of typo) -eq 2 && test \$(wc -l <typo.err) -eq 1 && grep -q \"no parameter named 'qa'\" typo.err"
run_capture range "$boot" --set IBz=1
check "an out-of-range value is a one-line error naming the range" \
  bash -c "test $(status_of range) -eq 2 && grep -q 'IBz = 1 is outside its range \[1e-06, 0.01\]' range.err"
run_capture rule "$boot" --set IBx=4e-4
check "moments that break the triangle inequality together are a one-line error naming the rule" \
  bash -c "test $(status_of rule) -eq 2 && test \$(wc -l <rule.err) -eq 1 && grep -q 'IBx = 0.0004 breaks a rule of the declaration: B.s central moments obey the triangle inequality' rule.err"
run_capture uniform "$boot" --set IBx=4.16667e-4 --set IBy=3.33333e-4 --set IBz=8.33333e-5 --quiet --output uniform.txt
check "a uniform plate of the boot's own mass and size runs and conserves its energy to 7 digits or more" \
  bash -c "test $(status_of uniform) -eq 0 && grep -qE 'Energy conserved to ([7-9]|1[0-9])\.[0-9] accurate digits' uniform.out"
run_capture notnumber "$boot" --set g=heavy
check "a value that is not a number is refused" grep -q "'heavy' is not a number" notnumber.err

run_capture schematic "$boot" --schematic
check "--schematic draws the tree (Graphviz) and the model at t = 0" \
  bash -c "grep -q '<svg' babyboot-tree.svg && grep -q 'Pin' babyboot-tree.svg && grep -q 'front: x right, y up' babyboot-t0.svg"

check "the handout's picture of the boot at t = 0 is the one the model draws" \
  cmp -s babyboot-t0.svg "$SOURCE_DIR/handouts/figures/babyboot-t0.svg"
if command -v gnuplot >/dev/null; then
  run_capture plot gnuplot -e "results='boot.txt'; out='boot.png'" "$SOURCE_DIR/handouts/plots/babyboot.gp"
  check "the handout's gnuplot script plots the boot's angles and energy" test -s boot.png -a "$(status_of plot)" -eq 0
fi

run_capture trade "$boot" --trade --final-time 1 --repeats 1
check "the trade table lists all nine integrators" \
  test "$(grep -cE '^(RungeKutta|ExplicitEuler|SemiExplicit|Verlet|CPodes)' trade.out)" -eq 9
# Each run under a cost cap, a count of evaluations (by default the reference run's own): the error-controlled
# methods of low order need tens of thousands of steps for 1e-7, and a cap of 2000 stops them, their rows saying so.
check "  each run stopped past the reference run's evaluations, which it says, with the most the table can take" \
  grep -qE '^babyboot: --trade: 9 integrators, 1 runs each, each stopped past [0-9]+ evaluations \(the reference run.s; ' trade.err
run_capture capped "$boot" --trade --final-time 1 --repeats 1 --max-evaluations 2000
check "--max-evaluations 2000: RungeKutta2 and explicit Euler are too costly, said where they stopped; Merson is not" \
  bash -c "test $(status_of capped) -eq 0 &&
           grep -qE '^RungeKutta2 +too costly: stopped past 2000 evaluations at t = [0-9.e-]+ s' capped.out &&
           grep -qE '^ExplicitEuler +too costly: stopped past 2000 evaluations' capped.out &&
           grep -qE '^RungeKuttaMerson +[0-9.]+ +[0-9]+ +[0-9]+ ' capped.out"

run_capture template "$BIN_DIR/project"
check "the template stops with status 3 at its first TODO" \
  bash -c "test $(status_of template) -eq 3 && grep -q 'not done yet (Project.cpp:' template.err"

run_capture templatehelp "$BIN_DIR/project" --help
check "and its --help shows the options all the same, saying declare() is not written yet" \
  bash -c "test $(status_of templatehelp) -eq 0 && grep -q -- '--set NAME=VALUE' templatehelp.out && grep -q 'declare() is not written yet' templatehelp.out"

run_capture new "$SIMLAB" project new myboot --from babyboot
check "simlab project new --from babyboot makes a project folder" \
  test -f myboot/Project.cpp -a -f myboot/project.toml -a -f myboot/CMakeLists.txt
selfcheck=$(grep ' check biosim Project.cpp$' new.out | awk '{ print $1 }')
check "its Next: lines name this simlab by a path that runs from the project's folder (simlab is not on the PATH)" \
  bash -c "cd myboot && test -x '$selfcheck' && '$selfcheck' --help >/dev/null"
run_capture newtemplate "$SIMLAB" project new mine
check "a project from the template names this simlab by its full path in its files, never build/bin/simlab" \
  bash -c "grep -qF 'Self-check:     $selfcheck check biosim Project.cpp' mine/Project.cpp && grep -qF '($selfcheck check biosim' mine/project.toml && ! grep -qE '(^|[^/])build/bin/simlab' mine/Project.cpp mine/project.toml"
check "and the copy's description names its own program, ./build/myboot, and its drawings" \
  bash -c "grep -q '\`./build/myboot --schematic\`' myboot/project.toml && grep -q '(myboot-tree.svg)' myboot/project.toml && ! grep -q babyboot myboot/project.toml"
run_capture again "$SIMLAB" project new myboot
check "and will not overwrite it" bash -c "test $(status_of again) -eq 2 && grep -q 'already exists' again.err"
run_capture badname "$SIMLAB" project new 'my boot'
check "a name that cannot name a program is refused" test "$(status_of badname)" -eq 2
run_capture reserved "$SIMLAB" project new clean
check "and so is a name CMake keeps for its own targets" \
  bash -c "test $(status_of reserved) -eq 2 && grep -q 'CMake keeps' reserved.err && test ! -e clean"
(cmake -S myboot -B myboot/build >cmake.log 2>&1 && cmake --build myboot/build >>cmake.log 2>&1)
check "the project builds with CMake against this simlab" test -x myboot/build/myboot || tail -20 cmake.log
run_capture myboot myboot/build/myboot --quiet --final-time 1
check "and runs as its own lab program" grep -q '^myboot: A swinging baby boot' myboot.out
finish
