# Nothing of a grading is another user's to read, at any moment: while simlab check grades the solution (with
# bubblewrap, and with limits only), a local user with no part in it (nobody) reads every file it can reach in every
# grading folder under /tmp, by listing and by the names simlab gives them. It must find none but the probe a test
# server opens to the tests' users once it is whole (the student's own compiled code, never a judge, rubric or
# source). Each folder is private from the moment it exists (createPrivateFolder), not made so later.
# The reader is a user id no other test runs simlab as (cli/isolation grades as nobody, whose own folders are its
# to read), and it looks only at gradings root owns, the ones this test starts.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

if [[ $(id -u) -ne 0 ]] || ! command -v setpriv >/dev/null; then
  echo "skipped: needs root and setpriv, to read as another user"
  exit 77
fi
cat >poll.py <<'PY'
import glob, os, sys, time
ready, stop = sys.argv[1], sys.argv[2]
seen, read = set(), set()
names = ["build", "probe"] + [f"judge{k}" for k in range(1, 5)]
for k in range(1, 5):
    names += [f"j{k}-server", f"j{k}-probes", f"j{k}-judge-home"]
    names += [f"j{k}-test{n}" for n in range(1, 17)] + [f"j{k}-program{n}" for n in range(1, 17)]
files = ["judge", "rubric.toml", "probe.so", "NewtonsApple.cpp", "NewtonsApple.o", "submission"]
allowed = lambda rel: rel.split("/")[0].endswith("-server") and rel.endswith("/probe.so")
first, caught = True, False
while not os.path.exists(stop):
    for root in glob.glob("/tmp/simlab-apple-*"):
        try:
            if os.lstat(root).st_uid != 0:
                continue
        except OSError:
            continue
        seen.add(root)
        for sub in names:
            folder = root + "/" + sub
            try:
                found = os.listdir(folder)
            except OSError:
                found = []
            for name in set(found) | set(files):
                path = folder + "/" + name
                try:
                    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
                except OSError:
                    continue
                os.close(fd)
                rel = path[len(root) + 1:]
                if os.path.isfile(path) and not allowed(rel):
                    read.add(rel)
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
  setpriv --reuid=65532 --regid=65532 --clear-groups /usr/bin/python3 poll.py "$mode.flags/ready" "$mode.flags/stop" \
    >"$mode.poll" 2>&1 &
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
  check "$mode: it read nothing of them" bash -c "! grep -q '^read ' '$mode.poll'"
done
finish
