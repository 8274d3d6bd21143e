# The instructor's terminal: a submission whose global constructor types a command into the terminal simlab was
# started from (ioctl TIOCSTI on /dev/tty and on its standard descriptors) and writes raw escape sequences to it
# (tests/corpus/apple/hostile/terminal-typist.toml) is checked in a real pseudo-terminal, with an interactive shell
# that goes on reading after simlab ends. In each sandbox mode nothing it typed may run and no escape sequence may
# reach the screen. A control first shows that this terminal would run what is typed into it, so that the check
# can fail.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

marker=/tmp/simlab-typed-by-a-submission
control=/tmp/simlab-typed-by-the-control
rm -f "$marker" "$control"
"$CORPUS" materialize apple "$SOURCE_DIR/tests/corpus/apple/hostile/terminal-typist.toml" --out cases >/dev/null
file=$PWD/cases/terminal-typist/NewtonsApple.cpp

# shell.py COMMAND [NAME=VALUE...]: an interactive bash in a new pseudo-terminal runs COMMAND, then, a second after
# it ends (time for anything typed into the terminal to reach the shell), exits. Prints everything the terminal
# showed, raw.
cat >shell.py <<'PY'
import os, pty, select, sys, time
command, settings = sys.argv[1], sys.argv[2:]
env = dict(os.environ, PS1="$ ", TERM="dumb", HISTFILE="/dev/null")
for setting in settings:
    name, value = setting.split("=", 1)
    env[name] = value
pid, fd = pty.fork()
if pid == 0:
    os.execvpe("bash", ["bash", "--norc", "--noprofile", "--noediting", "-i"], env)
seen = b""
def read(until, seconds):
    """Reads what the terminal shows for at most `seconds`, or until `until` has been seen (None: the whole time)."""
    global seen
    end = time.time() + seconds
    while time.time() < end:
        ready, _, _ = select.select([fd], [], [], 0.2)
        if not ready:
            continue
        try:
            chunk = os.read(fd, 65536)
        except OSError:
            return
        if not chunk:
            return
        seen += chunk
        if until is not None and until in seen:
            return
read(b"$ ", 10)
# The marker is split in the command line, so that its echo does not count as the end.
os.write(fd, (command + "; echo command-fin''ished\n").encode())
read(b"command-finished", 600)
read(None, 1.5)
os.write(fd, b"exit\n")
read(None, 10)
os.waitpid(pid, 0)
sys.stdout.buffer.write(seen)
PY

python3 shell.py "python3 -c 'import fcntl, termios; [fcntl.ioctl(0, termios.TIOCSTI, bytes([c])) for c in b\"touch $control\\n\"]'" \
  >control.transcript 2>&1
if [[ -e $control ]]; then
  pass "the control: a command typed into this terminal with TIOCSTI runs in the shell after the typist ends"
  rm -f "$control"
else
  echo "note: this kernel refuses TIOCSTI to every program here (dev.tty.legacy_tiocsti = 0): the attack cannot succeed even without simlab's defences"
fi

docker_caps=-all,+chown,+dac_override,+fowner,+fsetid,+kill,+setgid,+setuid,+setpcap,+net_bind_service,+net_raw,+sys_chroot,+mknod,+audit_write,+setfcap
for mode in bubblewrap Landlock "limits only"; do
  settings=()
  prefix=""
  case $mode in
    Landlock) settings=(SIMLAB_NO_BUBBLEWRAP=1) ;;
    "limits only") settings=(SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1) ;;
  esac
  # Without bubblewrap, as in Docker's containers: root with Docker's default capabilities only.
  if [[ $mode != bubblewrap && $(id -u) -eq 0 ]] && command -v setpriv >/dev/null; then
    prefix="setpriv --bounding-set $docker_caps --inh-caps=-all"
  fi
  name=${mode// /-}
  python3 shell.py "$prefix $SIMLAB check apple $file" "${settings[@]}" >"$name.transcript" 2>&1
  if [[ $mode != bubblewrap && -n $build_closed ]]; then
    # Below a folder closed to other users the throwaway users cannot reach the build: simlab says so and builds nothing.
    check "$mode: the build lies below $build_closed, closed to others: simlab refuses in one line, naming it" \
      grep -qF "in this sandbox ($mode) the tools run as throwaway users, who cannot reach" "$name.transcript"
  else
    check "$mode: simlab graded the typist (Score: 76/76 on the visible tests)" grep -q "Score: 76/76" "$name.transcript"
    check "$mode: the sandbox it names is $mode" grep -q "sandbox: $mode" "$name.transcript"
  fi
  check "$mode: nothing the submission typed ran after simlab ended" test ! -e "$marker"
  check "$mode: no escape sequence reached the terminal" bash -c "! grep -q \$'\\x1b' '$name.transcript'"
  check "$mode: nor the submission's words" bash -c "! grep -q 'the screen is mine' '$name.transcript'"
  rm -f "$marker"
done
finish
