# Helpers for simlab's scripted tests. Sourced; expects SIMLAB, SOURCE_DIR and BIN_DIR from ctest.
set -uo pipefail

failures=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }
check() { local what=$1; shift; if "$@"; then pass "$what"; else fail "$what"; fi; }
finish() { [[ $failures -eq 0 ]] && echo "all checks passed" && exit 0; echo "$failures check(s) failed"; exit 1; }

# run_capture NAME CMD...: runs CMD, keeping its stdout, stderr and status in $NAME.out, $NAME.err, $NAME.status
run_capture() {
  local name=$1; shift
  "$@" >"$name.out" 2>"$name.err" </dev/null
  echo $? >"$name.status"
}
status_of() { cat "$1.status"; }
