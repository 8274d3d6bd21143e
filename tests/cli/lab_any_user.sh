# An author's lab is one folder, whatever it is called and whoever runs simlab on it: examples/pendulum copied to a
# folder of another name and given to another user (nobody, as a TA on the course's machine would be) verifies as
# that user with this build's simlab, which keeps that user's lab build and objects in their own cache (the
# build's is root's); and, from the folder above a lab whose folder is the program's name, simlab build says in one
# line that it will not write onto the folder, and writes the program where -o says.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
if [[ $(id -u) -ne 0 ]] || ! command -v setpriv >/dev/null; then
  echo "skipped: needs root and setpriv, to run simlab as another user"
  exit 77
fi
chmod 0755 "$work"
mkdir -p other/home
cp -r "$SOURCE_DIR/examples/pendulum" other/lab_b
chown -R 65534:65534 other
as_nobody=(env HOME="$work/other/home" XDG_CACHE_HOME= SIMLAB_CACHE= setpriv --reuid=65534 --regid=65534 --clear-groups)
(cd other && "${as_nobody[@]}" "$SIMLAB" assignment verify lab_b -j 2 >../verify.out 2>../verify.err; echo $? >../verify.status)
sed 's/^/    /' verify.out | grep -v ' as expected$'
check "another user verifies the lab in a folder of another name: every check holds" \
  bash -c "test $(status_of verify) -eq 0 && grep -q '^ok    build: pendulum' verify.out && grep -q '^verify: .* 0 fail' verify.out"
check "  each corpus case its expected score" \
  test "$(grep -c '^ok    corpus .* as expected$' verify.out)" -eq "$(ls other/lab_b/corpus/*.toml | wc -l)"
check "  the lab built in that user's own cache" \
  bash -c "ls -d other/home/.cache/simlab/*/labs/lab_b-* >/dev/null && test \$(stat -c %u other/home/.cache/simlab) -eq 65534"

# From the folder above a lab named as its program: never onto the folder. (Its own cache: a lab the build's cache
# knew would be one of simlab's places for every other test while this one runs. Its layout is cli/isolation's,
# whose lab build's objects it takes: lab_objects, tests/smoke/lib.sh.)
export SIMLAB_CACHE=$work/cache
mkdir labs && cp -r "$SOURCE_DIR/examples/pendulum" labs/pendulum
(cd labs && env "${lab_objects[@]}" "$SIMLAB" build ./pendulum pendulum/solution/Pendulum.cpp >../onto.out 2>../onto.err
 echo $? >../onto.status)
check "simlab build from the folder above: one line, exit 2, the lab's folder untouched" \
  bash -c "test $(status_of onto) -eq 2 && test \$(grep -c '^simlab: error: ' onto.err) -eq 1 &&
    grep -q \"'pendulum' is a folder, not where a program can be written: give -o PATH\" onto.err && test -d labs/pendulum/grading"
(cd labs && env "${lab_objects[@]}" "$SIMLAB" build ./pendulum pendulum/solution/Pendulum.cpp -o swing >../built.out 2>../built.err; echo $? >../built.status)
check "  and with -o it builds the program there, which runs" \
  bash -c "test $(status_of built) -eq 0 && labs/swing --help | grep -q '^Usage: pendulum'"
finish
