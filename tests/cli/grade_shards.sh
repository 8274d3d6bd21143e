# simlab grade --shard I/N: three shards, each with an object cache of its own as on three machines, grade the
# sample class side by side into one --out; the whole-class run then assembles a gradebook identical to one
# machine's (cli/grade-sample-class's, $FIXTURES/apple-graded), grading nothing again. A copy of the build's judge elsewhere, with other times, keeps every record
# (the key is content, not paths or times). The locks: a shard runs beside the others, a second copy of one
# shard stops, and a whole-class run stops while any shard runs.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

cp -r "$BIN_DIR/../sample-class/apple" class
students=$(ls class | wc -l)
student_lines() { grep -cE '^  [a-z0-9-]+ +[0-9.]+/100 ' "$1"; }

for i in 1 2 3; do
  SIMLAB_CACHE=$PWD/cache$i "$SIMLAB" grade apple class --out grades --shard "$i/3" --jobs 1 >"shard$i.out" 2>"shard$i.err" </dev/null &
done
wait
for i in 1 2 3; do
  check "shard $i/3 finishes and says how to assemble" grep -q "once every shard has finished" "shard$i.out"
done
shares=$(( $(student_lines shard1.out) + $(student_lines shard2.out) + $(student_lines shard3.out) ))
check "the shards graded every student once between them ($shares of $students)" test "$shares" -eq "$students"
check "the shards are a fair split ($(( (students + 2) / 3 )), ... and $(( students / 3 )) of $students)" \
  test "$(student_lines shard1.out)-$(student_lines shard3.out)" = "$(( (students + 2) / 3 ))-$(( students / 3 ))"
check "a shard writes no gradebook, summary or report" bash -c '! ls grades/gradebook.csv grades/summary.csv grades/report.html 2>/dev/null'
check "every student has a record" test "$(ls grades/students/*/record.json | wc -l)" -eq "$students"

run_capture assemble "$SIMLAB" grade apple class --out grades --jobs 2
check "the assembly succeeds" test "$(status_of assemble)" -eq 0
check "and grades nothing again" grep -q "^0 graded, $students up to date and kept" assemble.out
check "it writes the gradebook, the summary and the report" test -f grades/gradebook.csv -a -f grades/summary.csv -a -f grades/report.html

check "the gradebook is the same as one machine's" cmp -s grades/gradebook.csv "$FIXTURES/apple-graded/gradebook.csv"
check "and so is the summary" cmp -s grades/summary.csv "$FIXTURES/apple-graded/summary.csv"

# The same judge at another path, with other times: the records stay (a manifest that names the copy).
judge=$(python3 -c 'import json, sys
print(next(a["judge"] for a in json.load(open(sys.argv[1]))["assignments"] if a["id"] == "apple"))' "$BIN_DIR/../simlab-build.json")
copy=$judge.copy-$$
cp "$judge" "$copy" && touch -d '2001-02-03 04:05:06' "$copy"
sed "s|\"$judge\"|\"$copy\"|" "$BIN_DIR/../simlab-build.json" >moved.json
run_capture moved env SIMLAB_MANIFEST="$PWD/moved.json" "$SIMLAB" grade apple class --out grades --jobs 2
rm -f "$copy"
check "the manifest names the copy" grep -q "apple-judge.copy-$$" moved.json
check "a copy of the judge elsewhere, with other times, regrades nothing (content, not stamps)" \
  grep -q "^0 graded, $students up to date and kept" moved.out

# Locks: shards share the folder; each shard is one process at a time; a whole-class run waits for no shard.
run_capture beside flock -s grades/.simlab-lock "$SIMLAB" grade apple class --out grades --shard 1/3
check "a shard runs while another shard holds the folder" test "$(status_of beside)" -eq 0
check "and, run again, it grades nothing ($(( (students + 2) / 3 )) up to date)" \
  grep -q "^0 graded, $(( (students + 2) / 3 )) up to date and kept" beside.out
run_capture twice flock grades/.simlab-lock-shard-2-of-3 "$SIMLAB" grade apple class --out grades --shard 2/3
check "a second copy of one shard stops in one line" \
  bash -c "test $(status_of twice) -eq 2 && test \$(wc -l <twice.err) -eq 1 && grep -q 'shard 2-of-3 of grades is being graded already' twice.err"
run_capture whole flock -s grades/.simlab-lock "$SIMLAB" grade apple class --out grades
check "the whole-class run stops while a shard runs" \
  bash -c "test $(status_of whole) -eq 2 && grep -q 'another simlab is writing into grades' whole.err"

# Bad shards: one line each, exit status 2, nothing graded.
for bad in 0/3 4/3 3 1/0 a/b 1/3x; do
  run_capture "bad-${bad//\//-}" "$SIMLAB" grade apple class --out bad --shard "$bad"
  check "--shard $bad is refused in one line" \
    bash -c "test \$(cat 'bad-${bad//\//-}.status') -eq 2 && test \$(wc -l <'bad-${bad//\//-}.err') -eq 1 && grep -q -- '--shard' 'bad-${bad//\//-}.err'"
done
run_capture clash "$SIMLAB" grade apple class --out bad --shard 1/2 --only reference
check "--shard with --only is refused" bash -c "test $(status_of clash) -eq 2 && grep -q 'give --only to that run' clash.err"
check "nothing was graded by a refused command" test ! -e bad/students
finish
