# The starter code, what students read first and edit, is laid out as the project's .clang-format says: a student
# whose editor formats on save (VS Code, CLion, Emacs and Vim with clang-format) changes nothing but their own lines.
# The check fails naming each file that clang-format would change, with its first changed lines.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

format=$(command -v clang-format-14 || command -v clang-format || true)
if [[ -z $format ]]; then
  echo "skipped: clang-format is not installed (scripts/install-deps installs it)"
  exit 77
fi
mapfile -t files < <(cd "$SOURCE_DIR" && find starter -name '*.cpp' -o -name '*.h' | sort)
check "there is starter code to check (${#files[@]} files)" test "${#files[@]}" -ge 4
changed=0
for f in "${files[@]}"; do
  if ! (cd "$SOURCE_DIR" && "$format" --style=file "$f" | diff -u "$f" - >"$work/diff.txt"); then
    changed=$((changed + 1))
    echo "$f would change:"; head -n 12 "$work/diff.txt"
  fi
done
check "every starter file is as .clang-format lays it out" test "$changed" -eq 0
finish
