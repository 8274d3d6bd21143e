# simlab grade apple (README's first command): grades the bundled sample class - the apple's corpus - and prints one
# score per student; every student's score, outcomes, status and report are the corpus's (simlab-corpus compare):
# the proof, made once, that the grader grades the apple's cases right on every test. The graded class is kept in
# $FIXTURES/apple-graded for the tests that resume, shard or distribute grading, to compare theirs with.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

run_capture grade "$SIMLAB" grade apple
cat grade.out
check "grade exits 0" test "$(status_of grade)" -eq 0
check "the reference gets 100/100" grep -qE '^  reference +100/100' grade.out
check "the starter gets 0/100" grep -qE '^  starter +0/100' grade.out
check "a compile error is named" grep -qE '^  compile-error +0/100 +did not compile' grade.out
check "every sample student has a line" test "$(grep -c '/100' grade.out)" -eq "$(ls "$SOURCE_DIR"/tests/corpus/apple/*.toml | wc -l)"
run_capture compare "$CORPUS" compare apple "$SOURCE_DIR"/tests/corpus/apple/*.toml --grades grades/apple
sed 's/^/    /' compare.out
check "every student's score, outcomes and report are the corpus's" test "$(status_of compare)" -eq 0
rm -rf "$FIXTURES/apple-graded" && mkdir -p "$FIXTURES" && cp -r grades/apple "$FIXTURES/apple-graded"
finish
