# simlab's own code under AddressSanitizer and UndefinedBehaviorSanitizer: a Debug tree of its own beside the
# build (build/sanitize, kept between runs so that a rerun builds only what changed) runs the unit tests and
# grades a sample of the corpus, hostile submissions among them. The probes are linked with the sanitizers'
# runtimes (the manifest's link line says so in this tree). Any sanitizer report fails the test.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

tree=$(cd "$BIN_DIR/.." && pwd)/sanitize
jobs=${SIMLAB_JOBS:-2}
# Compiled by clang++ (the student files' compiler, which scripts/install-deps installs), which builds this tree in
# about a third of GCC's time: what is checked is simlab's code, whichever compiler instruments it.
compiler=()
clang=$(command -v clang++-14 || command -v clang++ || true)
[[ -n $clang ]] && compiler=(-DCMAKE_CXX_COMPILER="$clang")
# Debug information of line tables alone (-g1): a report still names each frame's file and line, and the tree builds
# in a fifth less CPU time than with -g (261 against 318 s, measured).
run_capture configure cmake -S "$SOURCE_DIR" -B "$tree" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
  -DSIMLAB_SANITIZE=ON -DSIMLAB_BUILD_STUDIES=OFF "${compiler[@]}"
check "the sanitizer tree configures (Debug, -fsanitize=address,undefined, ${clang:-the default compiler})" \
  test "$(status_of configure)" -eq 0
[[ $(status_of configure) -eq 0 ]] || tail -n 20 configure.err
# Only what the checks below run: the unit tests, the corpus runner and what grading each lab needs (its judge and
# every object and library a probe is linked from: <lab>_grading), not the studies, the lab programs or the test
# tools.
graders=()
for lab in apple projectile book biosim; do graders+=("${lab}_grading"); done
run_capture build cmake --build "$tree" -j "$jobs" --target unit_tests simlab-corpus "${graders[@]}"
check "and builds" test "$(status_of build)" -eq 0
if [[ $(status_of build) -ne 0 ]]; then grep -m 20 -E 'error|Error' build.out build.err; finish; fi

# A report of either sanitizer ends the process with a failure, and says so on stderr.
export ASAN_OPTIONS=abort_on_error=0:halt_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
run_capture unit "$tree/bin/unit_tests"
check "the unit tests pass with both sanitizers ($(grep -oE '[0-9]+ test cases' unit.out))" \
  bash -c "test $(status_of unit) -eq 0 && ! grep -qE 'ERROR: (Address|Leak)Sanitizer|runtime error:' unit.out unit.err"
[[ $(status_of unit) -eq 0 ]] || grep -m 20 -E 'FAILED|Sanitizer|runtime error' unit.out unit.err

# The corpus cases graded by the sanitized simlab: the verdicts are the same, and nothing simlab, a judge or the
# course's side of a probe runs reports anything.
for case in apple/reference apple/starter apple/segfault apple/infinite-loop apple/hostile/attack-the-server \
            apple/hostile/fork-bomb projectile/reference book/reference biosim/honest-shank; do
  lab=${case%%/*}
  file=$SOURCE_DIR/tests/corpus/$case.toml
  [[ -f $file ]] || { fail "no corpus case $case"; continue; }
  name=${case//\//-}
  run_capture "$name" env SIMLAB_MANIFEST="$tree/simlab-build.json" "$tree/bin/simlab-corpus" check "$lab" "$file"
  check "corpus $case keeps its expected score under the sanitizers" test "$(status_of "$name")" -eq 0
  [[ $(status_of "$name") -eq 0 ]] || tail -n 5 "$name.out" "$name.err"
done
check "no sanitizer report anywhere" bash -c "! grep -qE 'ERROR: (Address|Leak)Sanitizer|runtime error:' ./*.out ./*.err"
finish
