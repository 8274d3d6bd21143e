# The sandbox in each of its modes (bubblewrap; Landlock; limits only), and without bubblewrap also as root with
# Docker's default capabilities only (no CAP_SYS_ADMIN: the situation inside Gradescope's and PrairieLearn's
# containers). sandbox-check runs sandbox-try in the sandbox as a probe is run and checks every rule; then simlab
# itself refuses hidden tests where a test could read them, and says how to fix that in one line.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

docker_caps=-all,+chown,+dac_override,+fowner,+fsetid,+kill,+setgid,+setuid,+setpcap,+net_bind_service,+net_raw,+sys_chroot,+mknod,+audit_write,+setfcap
as_docker=()
if [[ $(id -u) -eq 0 ]] && command -v setpriv >/dev/null; then
  as_docker=(setpriv --bounding-set "$docker_caps" --inh-caps=-all)
fi

run_mode() {  # run_mode NAME [NAME=VALUE...] -- [PREFIX...]: sandbox-check in that mode
  local name=$1; shift
  local settings=()
  while [[ $# -gt 0 && $1 != -- ]]; do settings+=("$1"); shift; done
  shift
  run_capture "$name" env "${settings[@]}" "$@" "$SANDBOX_CHECK" "$SANDBOX_TRY"
  sed 's/^/    /' "$name.out"
}

run_mode bwrap --
check "bubblewrap: every rule holds" test "$(status_of bwrap)" -eq 0
check "bubblewrap: the mode is bubblewrap here" grep -q '^sandbox: bubblewrap' bwrap.out

run_mode landlock SIMLAB_NO_BUBBLEWRAP=1 --
if grep -q '^sandbox: Landlock' landlock.out; then
  check "Landlock: every rule holds" test "$(status_of landlock)" -eq 0
  if [[ ${#as_docker[@]} -gt 0 ]]; then
    run_mode landlock-docker SIMLAB_NO_BUBBLEWRAP=1 -- "${as_docker[@]}"
    check "Landlock with Docker's capabilities: every rule holds" test "$(status_of landlock-docker)" -eq 0
  fi
else
  echo "skipped: Landlock (this kernel has none, or it is blocked here)"
fi

run_mode limits SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 --
check "limits only: every rule holds, and the audit names what a test could read" test "$(status_of limits)" -eq 0
if [[ ${#as_docker[@]} -gt 0 ]]; then
  run_mode limits-docker SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 -- "${as_docker[@]}"
  check "limits only with Docker's capabilities: every rule holds" test "$(status_of limits-docker)" -eq 0

  mkdir -p class/alice
  cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" class/alice/
  if [[ -n $build_closed ]]; then
    # The build lies below a folder other users may not enter: the throwaway users could build nothing, and simlab
    # says so in one line, before grading anyone.
    for command in grade check; do
      args=(grade apple class --out grades)
      [[ $command == check ]] && args=(check apple class/alice/NewtonsApple.cpp)
      run_capture "closed-$command" env SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 "${as_docker[@]}" "$SIMLAB" "${args[@]}"
      check "the build lies below $build_closed, closed to others: simlab $command refuses (exit 2), grading nothing" \
        bash -c "test $(status_of "closed-$command") -eq 2 && test ! -e grades/gradebook.csv"
      check "in one line naming the folder and the fix (chmod o+x $build_closed)" \
        bash -c "test \$(wc -l <closed-$command.err) -le 2 && grep -qF 'cannot reach' closed-$command.err && grep -qF '($build_closed is closed to others)' closed-$command.err && grep -qF 'chmod o+x $build_closed,' closed-$command.err"
    done
    echo "skipped: the audit of what a test could read, and the visible tests, in this mode (the build lies below $build_closed)"
    finish
  fi
  # simlab refuses to run hidden tests where a test could read them, in one line that says how to fix it.
  run_capture refused env SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 "${as_docker[@]}" "$SIMLAB" grade apple class --out grades
  check "limits only, files readable by all: simlab grade refuses (exit 2), grading nothing" \
    bash -c "test $(status_of refused) -eq 2 && test ! -e grades/gradebook.csv"
  check "in one line naming a file of the course it could read and the command that closes them" \
    bash -c "test \$(wc -l <refused.err) -le 2 && grep -qE \"could read $SOURCE_DIR/.* so hidden tests are not run: close them with .simlab lock. \" refused.err"
  run_capture visible env SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 "${as_docker[@]}" "$SIMLAB" check apple \
    class/alice/NewtonsApple.cpp
  check "the visible tests still run there (a self-check holds no secret): 76/76" grep -q 'Score: 76/76' visible.out
fi
finish
