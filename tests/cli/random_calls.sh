# System calls at random in each mode, then the walk (tests/corpus/apple/invariants/random-calls.toml,
# tests/corpus/calls.inc): from a test's call, processes of the test's own make calls of random numbers with random
# arguments, mostly what the students' filter allows and what it refuses, on the test's folder, the shared temporary
# folders, a bait file, simlab's places and the system's secrets; then one of them walks what it can read, and the
# test's process too. In bubblewrap, Landlock and limits only (as root: a throwaway user), no refused call may go
# through, no process may gain privilege, nothing may be read outside what a test may read (with limits only, simlab
# refuses hidden tests while anything is), and the host must be as it was: no file left in the shared temporary
# folders, no process of the test's left, the bait and simlab's files unchanged. The draw is new each run
# (SIMLAB_CALLS_SEED repeats one; the seed is in each mode's line).
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

case=$SOURCE_DIR/tests/corpus/apple/invariants/random-calls.toml

# calls_mode NAME MODE [NAME=VALUE...]: the calls and the walks where simlab's sandbox line names MODE
calls_mode() {
  local name=$1 mode=$2; shift 2
  run_capture "$name" env "$@" "$CORPUS" invariants apple "$case"
  grep -E '^(sandbox|limits only|OK|FAILED|skipped|    )' "$name.out" | sed 's/^/    /'
  if [[ $mode == Landlock ]] && ! grep -q '^sandbox: Landlock' "$name.out"; then
    echo "skipped: Landlock (this kernel has none, or it is blocked here)"
    return
  fi
  check "$name: the sandbox is $mode" grep -q "^sandbox: $mode" "$name.out"
  if grep -q '^skipped' "$name.out"; then return; fi
  check "$name: no refused call went through, no privilege, nothing read outside what a test may read, the host as it was" \
    test "$(status_of "$name")" -eq 0
  check "$name: calls were made, and a process of theirs walked after them, as did the test's" \
    grep -qE '^OK +random-calls: .*random calls: [1-9][0-9]* tried.* 0 otherwise\).*walk: [1-9].*walk: [1-9]' "$name.out"
}

calls_mode bubblewrap bubblewrap
if [[ -n $build_closed ]]; then
  echo "skipped: Landlock and limits only (the build lies below $build_closed, which their throwaway users cannot enter)"
else
  calls_mode landlock Landlock SIMLAB_NO_BUBBLEWRAP=1
  calls_mode limits "limits only" SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1
fi
finish
