# The commands the README and docs/ name are commands simlab has: for each `simlab ...` (or `build/bin/simlab ...`)
# in inline code or on a "$ " line of an example, the subcommand's --help exists and lists every --option the text
# gives it, so that no page tells a reader of a command or an option that is not there. The examples that run in
# CI are also compared with their output (handout-check); this checks the ones that cannot run there too.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

pages=("$SOURCE_DIR/README.md" "$SOURCE_DIR"/docs/*.md)
named=0
while IFS= read -r snippet; do
  # The words after "simlab": the subcommand path is the longest prefix of plain words whose --help works.
  read -ra words <<<"${snippet#*simlab }"
  path=()
  for word in "${words[@]}"; do
    [[ $word =~ ^[a-z][a-z-]*$ ]] || break
    "$SIMLAB" "${path[@]}" "$word" --help >/dev/null 2>&1 || break
    path+=("$word")
  done
  if [[ ${#path[@]} -eq 0 ]]; then
    # `simlab --help` or `simlab COMMAND --help` (a placeholder) name no command; a plain word must be one.
    [[ ${words[0]} =~ ^[a-z][a-z-]*$ ]] && fail "\`$snippet\`: simlab has no command ${words[0]}"
    continue
  fi
  named=$((named + 1))
  help=$("$SIMLAB" "${path[@]}" --help 2>&1)
  for word in "${words[@]}"; do
    [[ $word =~ ^--[a-z][a-z-]*$ ]] || continue
    grep -q -- "$word" <<<"$help" || fail "\`$snippet\`: simlab ${path[*]} has no option $word"
  done
done < <({ grep -oh '`[^`]*`' "${pages[@]}" | tr -d '`'; sed -n 's/^\$ //p' "${pages[@]}"; } | grep -E '^([A-Z_]+=[^ ]+ )*([a-z./]*/)?simlab [a-z]' |
         grep -vx 'simlab id' | sort -u)  # "simlab id": the roster's column of folder names, not a command
check "the README and docs/ name commands of simlab's ($named commands read)" test "$named" -ge 15
finish
