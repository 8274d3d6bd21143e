# The same figures on every x86-64 machine (simlab/reproducible_math.h):
#  - no program of the project calls a long double libm function that glibc computes with the x87 instructions
#    F2XM1, FYL2X, FPATAN or FPTAN, which Intel's and AMD's processors round differently;
#  - the study programs and the lab programs print the same bytes (times aside) here and on an emulated processor
#    without FMA, AVX2 or AVX-512 (qemu-x86_64 -cpu Nehalem), whose libm takes other code and whose x87 is QEMU's
#    own. Skipped where qemu-user is not installed (scripts/install-deps installs it for the tests);
#  - and the check can fail: without the mask, on a processor with FMA, the chaotic boot's run differs.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

# glibc's long double functions built on those instructions (from its x86_64 sources: e_powl.S, e_expl.S,
# e_logl.S, e_log10l.S, e_log2l.S, e_atan2l.c, s_atanl.c, s_expm1l.S, s_log1pl.S, and what calls them).
x87='^(pow|exp|exp2|exp10|expm1|log|log2|log10|log1p|atan|atan2|asin|acos|sinh|cosh|tanh|asinh|acosh|atanh|lgamma|tgamma|erf|erfc|tan)l$'
programs=()
# Every program that runs a simulation or grades one; the fuzz targets (bin/fuzz-*, clang's, with its sanitizers'
# runtime) are the tests' own tools and print no figure.
for f in "$BIN_DIR"/* "$BIN_DIR"/../judges/*; do
  [[ $f == "$BIN_DIR"/fuzz-* ]] && continue
  [[ -f $f && -x $f ]] && head -c 4 "$f" | grep -q ELF && programs+=("$f")
done
check "there are programs to look at (${#programs[@]})" test "${#programs[@]}" -ge 10
bad=""
for f in "${programs[@]}"; do
  calls=$(nm -D --undefined-only "$f" 2>/dev/null | awk '{ sub(/@.*/, "", $2); print $2 }' | grep -E "$x87" | tr '\n' ' ')
  [[ -n $calls ]] && bad+="${f##*/}: $calls; "
done
check "no program calls an x87 transcendental (found: ${bad:-none})" test -z "$bad"

qemu=$(command -v qemu-x86_64 || true)
if [[ -z $qemu ]]; then
  echo "skipped: the runs on an emulated processor (qemu-x86_64 is not installed: apt-get install qemu-user)"
  finish
fi

# Times are the only figures allowed to differ: drop them (the study's "seconds" and "repeats", the programs'
# "... s of CPU" and timing lines).
same_study() {  # same_study NAME PROGRAM ARGS...: JSON lines without seconds, native against emulated
  local name=$1; shift
  "$@" 2>/dev/null | sed -E 's/"(seconds|repeats)":[^,}]*[,]?//g' >"$name.native"
  "$qemu" -cpu Nehalem "$@" 2>/dev/null | sed -E 's/"(seconds|repeats)":[^,}]*[,]?//g' >"$name.emulated"
  [[ -s $name.native ]] && cmp -s "$name.native" "$name.emulated"
}
# Every point up to a cap of 1000 evaluations (the emulator runs them about 30 times slower): each integrator's
# steps and the reference's long double integration, which is what a libm or an x87 would change.
check "the book's study (its reference's accuracy and every point) is the same on an emulated Nehalem" \
  same_study book "$BIN_DIR/book-study" --subject book-intermediate --max-evaluations 1000 --repeats 1
check "and it states its reference's accuracy" grep -q '"reference_digits":1[5-9]\.' book.native
check "the baby boot's study is the same on an emulated Nehalem" \
  same_study boot "$BIN_DIR/babyboot-study" --quick --max-evaluations 1000 --repeats 1

same_run() {  # same_run NAME PROGRAM ARGS...: the printed lines and the results file, native against emulated
  local name=$1; shift
  mkdir -p "$name/native" "$name/emulated"
  (cd "$name/native" && "$@" --output results.txt >out.txt 2>&1)
  (cd "$name/emulated" && "$qemu" -cpu Nehalem "$@" --output results.txt >out.txt 2>&1)
  [[ -s $name/native/results.txt ]] && cmp -s "$name/native/results.txt" "$name/emulated/results.txt" &&
    diff <(grep -v ' s\b' "$name/native/out.txt") <(grep -v ' s\b' "$name/emulated/out.txt") >/dev/null
}
check "the book program (w against the elliptic functions) prints the same on an emulated Nehalem" \
  same_run book-run "$BIN_DIR/book-reference" --spin intermediate --quiet
check "the baby boot (chaotic, Simbody's Pins turn by sin and cos) prints the same on an emulated Nehalem" \
  same_run boot-run "$BIN_DIR/babyboot" --final-time 5 --quiet

if grep -qw fma /proc/cpuinfo; then
  SIMLAB_NATIVE_MATH=1 "$BIN_DIR/babyboot" --final-time 5 --quiet --output control.txt >/dev/null 2>&1
  check "the control: with the processor's own FMA libm (SIMLAB_NATIVE_MATH=1) the boot's run differs" \
    bash -c "test -s control.txt && ! cmp -s control.txt boot-run/native/results.txt"
else
  echo "skipped: the control (this processor has no FMA, so its libm is the reproducible one already)"
fi
finish
