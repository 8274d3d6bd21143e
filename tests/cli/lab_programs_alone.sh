# The lab programs alone, as on a system without the grader's libraries (the native route the student README gives
# for macOS and Windows without containers): cmake -DSIMLAB_GRADER=OFF configures, builds a lab program and its
# reference from the course's sources, and the reference runs to its digits.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

# A copy of the course's sources (not the build or the history), built in its own build/ as the build under test is
# beside its sources: the objects it shares with that build come from that build's ccache (shared_objects), since
# every path is the same relative to the copy.
build=$(cd "$BIN_DIR/.." && pwd)
mkdir source
tar -C "$SOURCE_DIR" --exclude=./.git --exclude="./${build#"$SOURCE_DIR"/}" -cf - . | tar -C source -xf -
shared_objects "$work/source"
run_capture configure cmake -S source -B source/build -DSIMLAB_GRADER=OFF -DSIMLAB_CCACHE=OFF ${shared_objects:+"$shared_objects"}
check "cmake -DSIMLAB_GRADER=OFF configures" test "$(status_of configure)" -eq 0
[[ $(status_of configure) -eq 0 ]] || tail -n 20 configure.err
run_capture build cmake --build source/build -j 2 --target apple apple-reference
check "and builds the apple's program and its reference" test -x source/build/bin/apple -a -x source/build/bin/apple-reference
[[ -x source/build/bin/apple-reference ]] || grep -m 20 -E 'error|Error' build.out build.err
run_capture starter source/build/bin/apple --quiet
check "the starter's program stops at its first TODO, saying where" grep -q 'not done yet (NewtonsApple.cpp:' starter.err
run_capture reference source/build/bin/apple-reference --quiet
check "the reference runs and counts its digits" bash -c "test $(status_of reference) -eq 0 && grep -qi 'digits' reference.out"
finish
