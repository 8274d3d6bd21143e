# simlab grade apple: grades the bundled sample class and prints one score per student.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

run_capture grade "$SIMLAB" grade apple
cat grade.out
check "grade exits 0" test "$(status_of grade)" -eq 0
check "the reference gets 100/100" grep -qE '^  reference +100/100' grade.out
check "the starter gets 0/100" grep -qE '^  starter +0/100' grade.out
check "a compile error is named" grep -qE '^  compile-error +0/100 +did not compile' grade.out
check "every sample student has a line" test "$(grep -c '/100' grade.out)" -eq "$(ls "$SOURCE_DIR"/tests/corpus/apple/*.toml | wc -l)"
finish
