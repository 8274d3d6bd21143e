# Helpers for simlab's scripted tests. Sourced; expects SIMLAB, SOURCE_DIR and BIN_DIR from ctest.
set -uo pipefail

failures=0
script_started=${EPOCHREALTIME/[.,]/}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }
check() { local what=$1; shift; if "$@"; then pass "$what"; else fail "$what"; fi; }
# A failed script keeps what its commands printed (each NAME.out, .err and .status of run_capture below, the first
# MB of each) in the build's Testing/failed/<script>-<pid>, open to its owner alone, and says where: a failure in a
# long run can be read after it.
keep_outputs() {
  [[ -n ${BIN_DIR:-} ]] || return 0
  local kept file
  kept=$(cd "$BIN_DIR/.." && pwd)/Testing/failed/$(basename "$0" .sh)-$$
  (umask 077 && mkdir -p "$kept") || return 0
  for file in "$work"/*.out "$work"/*.err "$work"/*.status; do
    [[ -f $file ]] && head -c 1048576 "$file" >"$kept/${file##*/}"
  done
  echo "what its commands printed: $kept"
}
# The steps of 5 s or more (run_capture's), longest first, in one line: where a slow test spends its time.
slow_steps() {
  local entry line=""
  while read -r entry; do
    line+=", ${entry#* } $((${entry%% *} / 10)).$((${entry%% *} % 10)) s"
  done < <(printf '%s\n' "${step_tenths[@]}" | sort -rn | awk '$1 >= 50')
  [[ -z $line ]] || echo "steps of 5 s or more: ${line#, }"
}
# The test's time in one line: its wall-clock time and its CPU time (user and system: its shell's and that of every
# command it waited for, as bash's `times` counts them; a daemon it started is not counted). On a machine whose cores
# are all busy, the CPU time is what a test costs the suite; a test whose CPU time is a small part of its run waits.
time_spent() {
  times >"$work/.times" 2>/dev/null || return 0
  local cpu wall
  wall=$(((${EPOCHREALTIME/[.,]/} - script_started) / 100000))
  # Four fields, 0m1.234s: the shell's user and system time, then its waited-for children's.
  cpu=$(tr , . <"$work/.times" |
        awk '{ for (i = 1; i <= NF; i++) { split($i, t, "m"); sub("s", "", t[2]); s += 60 * t[1] + t[2] } }
             END { printf "%.1f", s }')
  echo "time: $((wall / 10)).$((wall % 10)) s, $cpu s of it CPU time (the test's and every command's it waited for)"
}
finish() {
  slow_steps
  time_spent
  [[ $failures -eq 0 ]] && echo "all checks passed" && exit 0
  echo "$failures check(s) failed"; keep_outputs; exit 1
}

# run_capture NAME CMD...: runs CMD, keeping its stdout, stderr and status in $NAME.out, $NAME.err, $NAME.status
# (and its wall-clock time, in tenths of a second, for slow_steps)
step_tenths=()
run_capture() {
  local name=$1 started=${EPOCHREALTIME/[.,]/}; shift
  "$@" >"$name.out" 2>"$name.err" </dev/null
  echo $? >"$name.status"
  step_tenths+=("$(((${EPOCHREALTIME/[.,]/} - started) / 100000)) $name")
}
status_of() { cat "$1.status"; }

# closed_to_others PATH: the first folder on the way to PATH that other users may not pass through (empty if none).
# As root without bubblewrap, simlab's tools run as throwaway users, who must reach the build: below such a folder
# simlab refuses to build, in one line naming it. $build_closed is that folder for this build when we are root.
closed_to_others() {
  local path="" part parts
  IFS=/ read -ra parts <<<"${1#/}"
  for part in "${parts[@]}"; do
    path=$path/$part
    [[ -d $path ]] || return 0
    if (( (8#$(stat -c %a "$path") & 1) == 0 )); then echo "$path"; return 0; fi
  done
}
# shellcheck disable=SC2034  # read by the scripts that source this file
build_closed=""
# shellcheck disable=SC2034
if [[ $(id -u) -eq 0 && -n ${BIN_DIR:-} ]]; then build_closed=$(closed_to_others "$BIN_DIR"); fi

# shared_objects ROOT: sets $shared_objects to the cmake argument that compiles the copy of simlab in ROOT through
# ccache, in the cache of the build under test (BUILD/ccache, which its own objects filled; CMakeLists.txt says
# how): the same source with the same flags is the same object, taken from there (paths under ROOT are hashed as
# relative to it, as the build's are to its sources, so copies in other folders match). Empty without ccache: then
# each copy compiles everything.
shared_objects=""
shared_objects() {
  command -v ccache >/dev/null || return 0
  export CCACHE_DIR=$BIN_DIR/../ccache CCACHE_BASEDIR=$1 CCACHE_NOHASHDIR=1
  export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
  # shellcheck disable=SC2034  # read by the scripts that source this file
  shared_objects=-DCMAKE_CXX_COMPILER_LAUNCHER=ccache
}

# lab_objects: NAME=VALUE settings (for env) under which an author's lab, which simlab builds with CMake in its
# cache, compiles through ccache, in the build's cache, paths under $work hashed as relative to the compiler's
# folder: tests that build the same lab in the same layout under their own $work (the lab in $work/labs/NAME, its
# build in SIMLAB_CACHE=$work/cache, this build's simlab) compile it once between them. For commands run as this
# user: another cannot write the cache. Empty without ccache.
lab_objects=()
if command -v ccache >/dev/null && [[ -n ${BIN_DIR:-} ]]; then
  # shellcheck disable=SC2034  # read by the scripts that source this file
  lab_objects=(CMAKE_CXX_COMPILER_LAUNCHER=ccache "CCACHE_DIR=$BIN_DIR/../ccache" "CCACHE_BASEDIR=$work" CCACHE_NOHASHDIR=1
               "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime")
fi
