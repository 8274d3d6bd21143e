# The isolation's invariants, in every mode this machine offers: no code of a submission runs as root or with a
# capability - whichever entry point it takes (tests/corpus/apple/invariants/: an ifunc's resolver, local or global,
# .preinit_array, constructors of priority 0 to 101, weak constructors, a thread started early, a replaced operator
# new or read()) - and nothing it can read lies outside what a test may read (isolation/reach.h): the walk of
# reach-walk.toml opens every file it can list from / and from every place simlab names, as the test's user, and
# fails on any outside the allow-list. Each case is graded with the object check off, so that what is proved is the
# sandbox's design and not the check's; the witness in it records from wherever it ran. Modes: bubblewrap and
# Landlock, each with a probe's server and with a probe per test, Landlock and limits only as root with Docker's
# default capabilities, and not as root. Layouts: the course in this build tree, and a lab of one's own copied out
# of the tree with a history of its own (examples/pendulum, its hidden tests, solution and corpus closed as its author
# would). Where files are kept apart by their modes alone, simlab must refuse hidden tests while the walk finds
# anything (the tree here is open to all), naming a file and the command that closes it. The installed layouts (a
# prefix, /usr/local, a moved prefix) are tests/cli/install.sh's.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

cases=()
for case in "$SOURCE_DIR"/tests/corpus/apple/invariants/*.toml; do
  [[ $case == */random-calls.toml ]] || cases+=("$case")  # cli/random-calls runs that one, in each mode
done
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
  check "$name: no code of a submission ran with privilege or read beyond what a test may read" \
    test "$(status_of "$name")" -eq 0
  check "$name: the walk ran, and read the system" grep -qE 'reach-walk: .*walk: [1-9][0-9]* folders listed, [1-9][0-9]* files' "$name.out"
  if [[ $mode == "limits only" ]]; then
    # The tree is open to all here: simlab refuses hidden tests, rightly - the walk read what the refusal names.
    check "$name: simlab refuses hidden tests, naming a file of its places and the command that closes them" \
      grep -qE '^limits only: simlab refuses hidden tests here: .* could read /.* close them with .simlab lock' "$name.out"
    check "$name: rightly: the walk read files of simlab's places" grep -qE 'walk: .* [1-9][0-9]* outside what a test may read \(simlab refuses' "$name.out"
  else
    check "$name: the walk read nothing outside what a test may read" grep -qE 'walk: .* 0 outside what a test may read' "$name.out"
  fi
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

# A lab of one's own, copied out of the tree and given a history of its own, its secrets closed as an author closes
# them (the history is not: git makes its objects readable by all). The walk, in each mode, from that lab.
lab=$work/labs/pendulum
mkdir -p "$work/labs" && cp -r "$SOURCE_DIR/examples/pendulum" "$lab"
(cd "$lab" && git init -q && git add -A && git -c user.name=author -c user.email=author@example.edu commit -qm lab)
chmod -R go-rwx "$lab/grading/hidden.cpp" "$lab/solution" "$lab/corpus"
walk_case=$SOURCE_DIR/tests/corpus/pendulum/invariants/reach-walk.toml
# (Its build's objects, compiled once, are cli/lab-any-user's too: lab_objects, tests/smoke/lib.sh.)
lab_mode() {  # lab_mode NAME MODE [NAME=VALUE...]: the walk from the lab of one's own
  local name=$1 mode=$2; shift 2
  run_capture "$name" env SIMLAB_CACHE="$work/cache" "${lab_objects[@]}" "$@" "$CORPUS" invariants "$lab" "$walk_case"
  grep -E '^(sandbox|limits only|OK|FAILED|    )' "$name.out" | sed 's/^/    /'
  check "$name: the sandbox is $mode" grep -q "^sandbox: $mode" "$name.out"
  check "$name: nothing read outside what a test may read, the lab's history included" test "$(status_of "$name")" -eq 0
}
if [[ $(id -u) -eq 0 ]]; then chmod 0711 "$work" "$work/labs"; fi
lab_mode lab-bubblewrap bubblewrap
check "lab-bubblewrap: the walk read nothing outside what a test may read" \
  grep -qE 'walk: [1-9][0-9]* folders listed, [1-9][0-9]* files readable, 0 outside' lab-bubblewrap.out
if [[ -z $build_closed ]] && grep -q '^sandbox: Landlock' probe.out 2>/dev/null; then
  lab_mode lab-landlock Landlock SIMLAB_NO_BUBBLEWRAP=1
  check "lab-landlock: the walk read nothing outside what a test may read" \
    grep -qE 'walk: [1-9][0-9]* folders listed, [1-9][0-9]* files readable, 0 outside' lab-landlock.out
fi
if [[ -z $build_closed && $(id -u) -eq 0 ]]; then
  lab_mode lab-limits "limits only" SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1
  # The lab's history is open to all: simlab refuses hidden tests, naming a file of its places (the lab, its build, or
  # the course, also open here), and the lock that closes it.
  check "lab-limits: simlab refuses hidden tests, naming a file the walk read and the command that closes it" \
    bash -c "grep -qE '^limits only: simlab refuses hidden tests here: .* could read /.*close them with .simlab lock' lab-limits.out &&
      grep -qE 'walk: .* [1-9][0-9]* outside what a test may read \(simlab refuses' lab-limits.out"
  run_capture refuse-lab env SIMLAB_CACHE="$work/cache" "${lab_objects[@]}" SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 \
    "$SIMLAB" check "$lab" "$SOURCE_DIR/examples/pendulum/solution/Pendulum.cpp" --all
  check "simlab check --all refuses there in one line (exit 2)" \
    bash -c "test $(status_of refuse-lab) -eq 2 && test \$(grep -c . refuse-lab.err) -eq 1 && grep -q 'hidden tests are not run' refuse-lab.err"
  # Bad input: a lab simlab lock cannot close - a file of another user's, when the course's account locks it - is
  # refused in one line naming that file.
  if command -v setpriv >/dev/null; then
    mkdir -p "$work/theirs" && cp -r "$SOURCE_DIR/examples/pendulum" "$work/theirs/" && chown -R 65534:65534 "$work/theirs"
    chown 0:0 "$work/theirs/pendulum/handout.md" && chmod 0644 "$work/theirs/pendulum/handout.md"
    chmod 0755 "$work/theirs"
    run_capture lock-theirs env SIMLAB_CACHE="$work/cache-nobody" setpriv --reuid=65534 --regid=65534 --clear-groups \
      "$SIMLAB" lock "$work/theirs/pendulum"
    check "simlab lock of a lab holding another user's file: one line naming the file, exit 2" \
      bash -c "test $(status_of lock-theirs) -eq 2 && test \$(grep -c . lock-theirs.err) -eq 1 &&
        grep -q 'cannot close $work/theirs/pendulum/handout.md to other users (it is root.s' lock-theirs.err"
  fi
  # And one on a read-only file system (a bind mount of it, in a mount namespace of this test's own).
  if unshare --mount true 2>/dev/null; then
    mkdir -p "$work/readonly" && cp -r "$SOURCE_DIR/examples/pendulum" "$work/readonly/"
    run_capture lock-readonly env SIMLAB_CACHE="$work/cache" unshare --mount bash -c \
      "mount --bind '$work/readonly' '$work/readonly' && mount -o remount,bind,ro '$work/readonly' &&
       exec '$SIMLAB' lock '$work/readonly/pendulum'"
    check "simlab lock of a lab on a read-only file system: one line naming a file of it, exit 2" \
      bash -c "test $(status_of lock-readonly) -eq 2 && test \$(grep -c . lock-readonly.err) -eq 1 &&
        grep -q 'cannot close $work/readonly/pendulum.* to other users (it is on a read-only file system' lock-readonly.err"
  else
    echo "skipped: a read-only file system for simlab lock (no mount namespace here)"
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
