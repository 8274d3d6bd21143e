# A trade scene per student ([variants] per_student): the seed and the id pick the same scene on every run; check
# --student names it and grades on it; the same answer graded under two ids earns what each id's own scene gives
# (the apple's dt of 1e-2 s keeps 3 digits of a fall from 150 m, not of one from 40 m); a class's results.json has
# the leaderboard the grader measured; autograde reads the student from Gradescope's metadata. Off, nothing changes.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

trade="the trade: the fewest explicit Euler steps that keep 3 digits of the question's fall"
# The apple's trade test alone, under a rubric that gives each student a scene of their own.
cat >variants.toml <<TOML
assignment = "apple"
submission = "NewtonsApple.cpp"
[variants]
per_student = true
seed = "test seed"
[[test]]
name = "$trade"
points = 6
beyond = 0
full_within = 2
none_past = 10
TOML
sed '/^\[variants\]/,/^seed/d' variants.toml >plain.toml
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" .

# FNV-1a of "test seed", NUL, id, modulo the pool's 6: dee's is variant 1 (40 m), bob's variant 4 (150 m).
run_capture dee "$SIMLAB" check apple NewtonsApple.cpp --rubric variants.toml --student dee
run_capture dee2 "$SIMLAB" check apple NewtonsApple.cpp --rubric variants.toml --student dee
run_capture bob "$SIMLAB" check apple NewtonsApple.cpp --rubric variants.toml --student bob
check "check --student names the student's scene and its numbers" \
  grep -q '^Your trade scene (student dee, variant 1 of 6): variant 1: a fall from 40 m: {"dropHeight":40.0,"gravity":9.8} to 2 s$' dee.out
check "the same id gets the same scene and the same grade again" \
  diff <(grep -v 'compiled\|linked' dee.out) <(grep -v 'compiled\|linked' dee2.out)
check "another id another scene" grep -q '^Your trade scene (student bob, variant 4 of 6): variant 4: a fall from 150 m' bob.out
check "the copied dt earns nothing on dee's fall from 40 m: too few digits there" \
  grep -q "^      0/6 .*failed .*on your scene (variant 1: a fall from 40 m): ExplicitEuler, fixed step 0.01 s keeps 2.61 digits" dee.out
check "and full credit on bob's fall from 150 m" \
  grep -q "^      6/6 .*passed .*on your scene (variant 4: a fall from 150 m): ExplicitEuler, fixed step 0.01 s: " bob.out

run_capture noid "$SIMLAB" check apple NewtonsApple.cpp --rubric variants.toml
check "without an id, check says each student has their own scene and grades on the question's" \
  bash -c "grep -q '^Each student has a trade scene of their own' noid.out && grep -q '^Score: 6/6$' noid.out"
run_capture off "$SIMLAB" check apple NewtonsApple.cpp --rubric plain.toml --student dee
run_capture none "$SIMLAB" check apple NewtonsApple.cpp --rubric plain.toml
check "with [variants] off, --student changes nothing but a note: the question's scene, full marks" \
  bash -c "grep -q 'gives every student the same scene' off.err && grep -q '^Score: 6/6$' off.out &&
           diff <(grep '^ ' off.out | sed 's/ in [0-9.]* s//g') <(grep '^ ' none.out | sed 's/ in [0-9.]* s//g')"
run_capture badid "$SIMLAB" check apple NewtonsApple.cpp --rubric variants.toml --student $'a\tb'
check "an id with a control character is refused in one line" \
  bash -c "test $(status_of badid) -ne 0 && test \$(wc -l <badid.err) -eq 1"

# A class: each student's folder name is their id; both hand in the same file.
mkdir -p class/dee class/bob
cp NewtonsApple.cpp class/dee/ && cp NewtonsApple.cpp class/bob/
run_capture class "$SIMLAB" grade apple class --rubric variants.toml -o out -j 2
check "graded as a class, the copy earns 0 under dee's id and 6 under bob's" \
  bash -c "test $(status_of class) -eq 0 && grep -q '\"score\": 0' out/students/dee/results.json &&
           grep -q '\"score\": 6' out/students/bob/results.json"
check "bob's results.json is valid and has the leaderboard the grader measured" \
  "$VALIDATE" out/students/bob/results.json --score 6 --max 6 --tests 1
leaderboard() { python3 -c 'import json, sys; print(json.dumps(json.load(open(sys.argv[1])).get("leaderboard")))' "$1"; }
leaderboard out/students/bob/results.json >bob-board.json
check "its entries: 1.52 x the front (133) first, then 202 evaluations (200 steps), 3 digits kept (counted up to those asked)" \
  grep -qF '[{"name": "trade: x the front", "order": "asc", "value": 1.52}, {"name": "trade: evaluations", "order": "asc", "value": 202.0}, {"name": "trade: digits kept", "order": "desc", "value": 3.0}]' bob-board.json
check "an answer short of the digits asked is not on it" \
  test "$(leaderboard out/students/dee/results.json)" = "null"

# Gradescope's layout: the student is the first user's sid in submission_metadata.json beside the submission.
mkdir -p gs/submission gs/results
cp NewtonsApple.cpp gs/submission/
echo '{"users": [{"email": "dee@example.edu", "sid": "dee", "name": "Dee"}]}' >gs/submission_metadata.json
run_capture auto "$SIMLAB" autograde apple --submission gs/submission --results gs/results/results.json
check "autograde reads the metadata and writes a valid results.json with the leaderboard" \
  bash -c "test $(status_of auto) -eq 0 && '$VALIDATE' gs/results/results.json --score 100 --max 100 &&
           grep -q 'trade: evaluations' gs/results/results.json"
echo 'not json' >gs/submission_metadata.json
run_capture badmeta "$SIMLAB" autograde apple --submission gs/submission --results gs/results/results.json
check "metadata that is not JSON is an error the results.json says" \
  bash -c "test $(status_of badmeta) -ne 0 && grep -q 'submission_metadata.json is not JSON' gs/results/results.json"
finish
