# Nothing of a grading is another user's to read, at any moment: while simlab check grades the solution (with
# bubblewrap, and with limits only), a local user with no part in it (nobody) tries every file in every grading
# folder under $TMPDIR - by listing what it can, and by every name root sees there, since a folder it may pass
# through but not list still opens by name. It must read none: each test's probe is the test's own copy, in its
# own folder, and every folder is private from the moment it exists (createPrivateFolder), not made so later. Then a
# grading killed for good (SIGKILL) leaves its folder behind, which nobody can read either, and the next run removes
# in one line; simlab clean removes what is left.
# The reader is a user id no other test runs simlab as (cli/isolation grades as nobody, whose own folders are its
# to read), and it looks only at gradings root owns, the ones this test starts.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

if [[ $(id -u) -ne 0 ]] || ! command -v setpriv >/dev/null; then
  echo "skipped: needs root and setpriv, to read as another user"
  exit 77
fi
export TMPDIR=$work/tmp  # this test's gradings alone
mkdir -p "$TMPDIR" && chmod 1777 "$TMPDIR"
cat >poll.py <<'PY'
import glob, os, sys, time
ready, stop, tmp = sys.argv[1], sys.argv[2], sys.argv[3]
reader = 65532
seen, read = set(), set()
first, caught = True, False

def names(root):
    # Every file under a grading's folder, as root sees it (no link followed).
    found = []
    for folder, dirs, files in os.walk(root, onerror=lambda e: None):
        found += [os.path.join(folder, name) for name in files]
    return found

def opened_by_reader(paths):
    # Tried as the reader, in a child: a user with no part in the grading, no group, no capability.
    r, w = os.pipe()
    child = os.fork()
    if child == 0:
        os.close(r)
        os.setgroups([])
        os.setresgid(reader, reader, reader)
        os.setresuid(reader, reader, reader)
        out = os.fdopen(w, "w")
        for path in paths:
            try:
                fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
            except OSError:
                continue
            os.close(fd)
            out.write(path + "\n")
        out.close()
        os._exit(0)
    os.close(w)
    text = os.fdopen(r).read()
    os.waitpid(child, 0)
    return [line for line in text.split("\n") if line]

while not os.path.exists(stop):
    for root in glob.glob(tmp + "/simlab-apple-*"):
        try:
            if not os.path.isdir(root) or os.lstat(root).st_uid != 0:
                continue
        except OSError:
            continue
        seen.add(root)
        for path in opened_by_reader(names(root)):
            if os.path.isfile(path):
                read.add(path[len(root) + 1:])
    if first:
        open(ready, "w").close()
        first = False
    # A grading seen while it lived and gone since (a folder left behind by another run never goes).
    if not caught and any(not os.path.exists(root) for root in seen):
        open(os.path.join(os.path.dirname(ready), "saw"), "w").close()
        caught = True
    time.sleep(0.002)
gone = [root for root in seen if not os.path.exists(root)]
print(f"{len(gone)} grading folders seen while they lived")
for rel in sorted(read):
    print(f"read {rel}")
PY
chmod 0755 "$work" && chmod 0644 poll.py
solution=$SOURCE_DIR/solutions/apple/NewtonsApple.cpp
for mode in bubblewrap limits-only; do
  settings=()
  [[ $mode == limits-only ]] && settings=(SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1)
  # The reader looks from before the first grading starts until after the last has ended, however slow the
  # machine: the gradings wait for its first pass, go on (three at least) until it has seen one come and go, and
  # it stops when told.
  mkdir -m 0777 "$mode.flags"
  /usr/bin/python3 poll.py "$mode.flags/ready" "$mode.flags/stop" "$TMPDIR" >"$mode.poll" 2>&1 &
  poller=$!
  for _ in $(seq 600); do [[ -e $mode.flags/ready ]] && break; sleep 0.1; done
  for round in $(seq 20); do
    ((round > 3)) && [[ -e $mode.flags/saw ]] && break
    env "${settings[@]}" "$SIMLAB" check apple "$solution" --jobs 2 \
      --test "the apple starts at rest at the drop height" --test "the velocity follows v = -g t at every sample" \
      >"$mode.$round.out" 2>&1 </dev/null
  done
  touch "$mode.flags/stop"
  wait "$poller"
  sed 's/^/    /' "$mode.poll"
  check "$mode: the solution was graded while the reader looked" grep -q "passed" "$mode.1.out"
  check "$mode: the reader saw the gradings as they ran" grep -qE '^[1-9][0-9]* grading folders seen while they lived' "$mode.poll"
  check "$mode: it read nothing of them, by any name" bash -c "! grep -q '^read ' '$mode.poll'"
done

# A grading killed for good: its folder stays, closed to others, until the next run (or simlab clean) removes it.
env SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1 "$SIMLAB" check apple "$solution" --jobs 1 >killed.out 2>&1 </dev/null &
killed=$!
for _ in $(seq 600); do
  compgen -G "$TMPDIR/simlab-apple-*/probe/probe.so" >/dev/null && break
  sleep 0.1
done
kill -KILL "$killed"; wait "$killed" 2>/dev/null
mapfile -t left < <(find "$TMPDIR" -maxdepth 1 -name 'simlab-apple-*' -type d)
check "a grading killed for good leaves its folder behind" test ${#left[@]} -ge 1
listed=$(find "$TMPDIR" -type f | wc -l)
readable=$(find "$TMPDIR" -type f -print0 | setpriv --reuid=65532 --regid=65532 --clear-groups xargs -0 -r sh -c \
  'for f; do head -c1 -- "$f" >/dev/null 2>&1 && echo "$f"; done' sh | wc -l)
check "and nobody else can read any of its $listed files" test "$readable" -eq 0
run_capture next "$SIMLAB" check apple "$solution" --test "the apple starts at rest at the drop height"
check "the next run removes it, saying so in one line" \
  bash -c "grep -qE '^simlab: removed [0-9]+ folders? that a stopped run of simlab left behind: simlab-apple-' next.err &&
    test -z \"\$(find '$TMPDIR' -maxdepth 1 -name 'simlab-apple-*' -type d)\""
mkdir "$TMPDIR/simlab-apple-LEFT01" && touch "$TMPDIR/simlab-apple-LEFT01.held"
run_capture clean "$SIMLAB" clean
check "simlab clean removes what a stopped run left" \
  bash -c "grep -q 'simlab-apple-LEFT01' clean.err && test ! -e '$TMPDIR/simlab-apple-LEFT01'"
run_capture clean-again "$SIMLAB" clean
check "and says when nothing is left" grep -qx 'simlab clean: nothing left behind' clean-again.out
finish
