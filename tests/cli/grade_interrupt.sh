# simlab grade interrupted mid-compile - by SIGINT, by SIGTERM, by two quick Ctrl-Cs - and run again: the
# interrupt records nothing for a student it cut short (a compiler ended by simlab's own signal is not "did not
# compile"), and after the rerun every correct submission has full marks.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

students=16
# compiler_running PID: the student-file compiler - clang (its driver and its -cc1 process), or GCC's cc1plus where
# simlab is built for GCC - runs below process PID (this test's simlab; a sandbox's processes are its descendants
# too), whatever other tests compile beside it.
compiler_running() {
  ps -e -o pid=,ppid=,comm= | awk -v root="$1" '
    { parent[$1] = $2; name[$1] = $3 }
    END {
      for (p in name) {
        if (name[p] !~ /^(clang|clang\+\+(-[0-9]+)?|cc1plus)$/) continue
        for (q = parent[p]; q > 1; q = parent[q]) if (q == root) exit 0
      }
      exit 1
    }'
}
export TMPDIR=$PWD/tmp  # simlab's work folders: this test's own, to look for what is left
mkdir -p "$TMPDIR"
make_class() {  # make_class DIR TAG: distinct copies of the reference, so each one compiles
  for i in $(seq -w 1 $students); do
    mkdir -p "$1/s$i"
    { cat "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp"; echo "// $2 student $i"; } >"$1/s$i/NewtonsApple.cpp"
  done
}
rows() { tail -n +2 "$1/gradebook.csv" 2>/dev/null; }
wait_for_compiler() {  # wait_for_compiler GRADES PID: until two students are recorded and a compiler runs below PID
  for _ in $(seq 6000); do  # (at most 120 s)
    [[ $(rows "$1" | wc -l) -ge 2 ]] && compiler_running "$2" && return 0
    sleep 0.02
  done
  return 1
}
no_children() {  # no process of the interrupted grading is left (they die with simlab; allow them a moment)
  for _ in $(seq 50); do pgrep -f "$1" >/dev/null || return 0; sleep 0.1; done
  pgrep -af "$1"
  return 1
}

for sig in INT TERM; do
  make_class class-$sig $sig
  export SIMLAB_CACHE=$PWD/cache-$sig  # an empty object cache: every student compiles
  "$SIMLAB" grade apple class-$sig --out grades-$sig --jobs 2 >first-$sig.out 2>first-$sig.err </dev/null &
  batch=$!
  found=0
  wait_for_compiler grades-$sig $batch || found=$?
  kill -$sig $batch
  check "SIG$sig: a compiler was running when the signal came" test $found -eq 0
  wait $batch
  status=$?
  check "SIG$sig: simlab exits with status 130 (it was $status)" test $status -eq 130
  check "SIG$sig: it says how to go on" grep -q "Run the same command again" first-$sig.err
  check "SIG$sig: no student was recorded below full marks" test "$(rows grades-$sig | grep -vc ',100,100,graded,')" -eq 0
  check "SIG$sig: no 'did not compile' anywhere" bash -c "! grep -rq 'did not compile' grades-$sig"
  recorded=$(rows grades-$sig | wc -l)
  check "SIG$sig: the interrupt came part-way ($recorded of $students recorded)" test "$recorded" -ge 2 -a "$recorded" -lt $students
  run_capture second-$sig "$SIMLAB" grade apple class-$sig --out grades-$sig --jobs 2
  check "SIG$sig: the rerun succeeds" test "$(status_of second-$sig)" -eq 0
  check "SIG$sig: the rerun reuses the $recorded finished" test "$(grep -c '(unchanged)' second-$sig.out)" -eq "$recorded"
  check "SIG$sig: every student now has full marks" test "$(rows grades-$sig | grep -c ',100,100,graded,')" -eq $students
done

# A second Ctrl-C ends simlab at once; what it wrote is still whole.
make_class class-twice twice
export SIMLAB_CACHE=$PWD/cache-twice
"$SIMLAB" grade apple class-twice --out grades-twice --jobs 2 >twice.out 2>twice.err </dev/null &
batch=$!
wait_for_compiler grades-twice $batch
kill -INT $batch
sleep 0.05
start=$(date +%s%N)
kill -INT $batch
wait $batch
status=$?
took=$(( ($(date +%s%N) - start) / 1000000 ))
check "a second Ctrl-C: status 130 (it was $status)" test $status -eq 130
check "a second Ctrl-C: simlab is gone within a second (${took} ms)" test $took -lt 1000
check "a second Ctrl-C: no process of that grading is left running" no_children "$TMPDIR/"
check "a second Ctrl-C: the gradebook holds only complete rows" \
  test "$(rows grades-twice | grep -vc ',100,100,graded,')" -eq 0
run_capture third "$SIMLAB" grade apple class-twice --out grades-twice --jobs 2
check "after it, a rerun gives every student full marks" \
  test "$(rows grades-twice | grep -c ',100,100,graded,')" -eq $students
finish
