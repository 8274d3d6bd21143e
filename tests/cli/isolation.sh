# The isolation's invariants, in every mode this machine offers: no code of a submission runs as root or with a
# capability, and none reads a secret - whichever entry point it takes (tests/corpus/apple/invariants/: an ifunc's
# resolver, local or global, .preinit_array, constructors of priority 0 to 101, weak constructors, a thread started
# early, a replaced operator new or read()). Each case is graded with the object check off, so that what is proved is
# the sandbox's design and not the check's; the witness in it records from wherever it ran. Modes: bubblewrap and
# Landlock, each with a probe's server and with a probe per test, Landlock and limits only as root with Docker's
# default capabilities, and not as root. The installed layouts (a prefix, /usr/local, a moved prefix) are
# tests/cli/install.sh's.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

cases=("$SOURCE_DIR"/tests/corpus/apple/invariants/*.toml)
docker_caps=-all,+chown,+dac_override,+fowner,+fsetid,+kill,+setgid,+setuid,+setpcap,+net_bind_service,+net_raw,+sys_chroot,+mknod,+audit_write,+setfcap
as_docker=()
if [[ $(id -u) -eq 0 ]] && command -v setpriv >/dev/null; then
  as_docker=(setpriv --bounding-set "$docker_caps" --inh-caps=-all)
fi

# run_mode NAME MODE [NAME=VALUE...] -- [PREFIX...]: the invariants where simlab's sandbox line names MODE
run_mode() {
  local name=$1 mode=$2; shift 2
  local settings=()
  while [[ $# -gt 0 && $1 != -- ]]; do settings+=("$1"); shift; done
  shift
  run_capture "$name" env "${settings[@]}" "$@" "$CORPUS" invariants apple "${cases[@]}"
  grep -E '^(sandbox|limits only|OK|FAILED|    )' "$name.out" | sed 's/^/    /'
  check "$name: the sandbox is $mode" grep -q "^sandbox: $mode" "$name.out"
  check "$name: no code of a submission ran with privilege or read a secret" test "$(status_of "$name")" -eq 0
}

run_mode bubblewrap-server bubblewrap --
check "bubblewrap: the probes are forked by a server (the mode whose server holds CAP_SETUID)" \
  grep -q "tests forked by a probe's server" bubblewrap-server.out
run_mode bubblewrap-alone bubblewrap SIMLAB_NO_TEST_SERVER=1 --

if [[ -n $build_closed ]]; then
  echo "skipped: Landlock and limits only (the build lies below $build_closed, which their throwaway users cannot enter)"
else
  run_capture probe env SIMLAB_NO_BUBBLEWRAP=1 "$CORPUS" invariants apple "${cases[0]}"
  if grep -q '^sandbox: Landlock' probe.out; then
    run_mode landlock-server Landlock SIMLAB_NO_BUBBLEWRAP=1 --
    run_mode landlock-alone Landlock SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_TEST_SERVER=1 --
    if [[ ${#as_docker[@]} -gt 0 ]]; then
      run_mode landlock-docker Landlock SIMLAB_NO_BUBBLEWRAP=1 -- "${as_docker[@]}"
    fi
  else
    echo "skipped: Landlock (this kernel has none, or it is blocked here)"
  fi
  run_mode limits "limits only" SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 --
  if [[ ${#as_docker[@]} -gt 0 ]]; then
    run_mode limits-docker "limits only" SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 -- "${as_docker[@]}"
  fi
fi

# Not as root: a student's self-check, as the user who started simlab (nobody here), with its own cache.
if [[ $(id -u) -eq 0 && -z $build_closed ]] && command -v setpriv >/dev/null; then
  chmod 0711 "$work"
  mkdir -p student && chown 65534:65534 student
  as_student=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  run_mode student-bubblewrap bubblewrap HOME="$work/student" SIMLAB_CACHE="$work/student/cache" -- "${as_student[@]}"
  if grep -q '^sandbox: Landlock' probe.out 2>/dev/null; then
    run_mode student-landlock Landlock HOME="$work/student" SIMLAB_CACHE="$work/student/cache" SIMLAB_NO_BUBBLEWRAP=1 -- \
      "${as_student[@]}"
  fi
fi
finish
