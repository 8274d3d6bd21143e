# Every shell script of the project passes ShellCheck at the warning level: the setup scripts, CI's entry point,
# the page checks, the tests themselves, and the scripts simlab writes for a platform (grader/*/scripts/, before
# their @...@ words are filled in) - each read as bash, following what it sources.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

if ! command -v shellcheck >/dev/null; then
  echo "skipped: shellcheck is not installed (scripts/install-deps installs it)"
  exit 77
fi
scripts=("$SOURCE_DIR"/scripts/* "$SOURCE_DIR"/.ci/run "$SOURCE_DIR"/tests/pages/page-check
         "$SOURCE_DIR"/tests/pages/replay-check "$SOURCE_DIR"/tests/pages/svg-text-check "$SOURCE_DIR"/tests/*/*.sh
         "$SOURCE_DIR"/grader/*/scripts/*.sh)
run_capture lint shellcheck --external-sources --source-path=SCRIPTDIR --shell=bash --severity=warning "${scripts[@]}"
check "${#scripts[@]} scripts pass ShellCheck's warnings" test "$(status_of lint)" -eq 0
[[ $(status_of lint) -eq 0 ]] || head -n 40 lint.out
finish
