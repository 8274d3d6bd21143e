# simlab's grading engine, its isolation and its command pass clang-tidy with the project's .clang-tidy (every finding
# an error): each of their translation units in the build's compile_commands.json, read without GCC's precompiled
# header (clang cannot read it; every source includes what it uses), two at a time.
#   clang_tidy.sh            every unit (the whole suite's lint/clang-tidy, about a minute): a target's batches
#                            read as one (db/unit-<n>.cpp includes each), since clang-tidy's checks walk every
#                            header a unit includes, JSON's, TOML's and CLI11's among them, once a unit: the
#                            command's four batches take 22 s of CPU time as one, 70 s as four (measured)
#   clang_tidy.sh --changed  the units holding a source changed since the branch left main, or not yet committed
#                            (lint/clang-tidy-changed, in the `pr` tier)
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

tidy=$(command -v clang-tidy-14 || command -v clang-tidy || true)
if [[ -z $tidy ]]; then
  echo "skipped: clang-tidy is not installed (scripts/install-deps installs it)"
  exit 77
fi
build=$(cd "$BIN_DIR/.." && pwd)
[[ -f $build/compile_commands.json ]] || { fail "no $build/compile_commands.json (CMAKE_EXPORT_COMPILE_COMMANDS)"; finish; }
mkdir db
sources=$(python3 - "$build/compile_commands.json" db/compile_commands.json "${1:-}" <<'PY'
import json, os, shlex, sys
entries = []
for e in json.load(open(sys.argv[1])):
    f = e["file"]
    if not any(part in f for part in ("/simlab_engine.dir/", "/simlab.dir/", "/simlab_isolation.dir/",
                                      "/simlab-probe-host.dir/", "/simlab_filter.dir/", "/simlab_common.dir/", "/simlab_study_engine.dir/",
                                      "/grader/build/", "/grader/grading/", "/grader/writers/", "/grader/course/",
                                      "/grader/common/", "/grader/study/", "/grader/cli/", "/grader/isolation/")):
        continue
    if f.endswith("cmake_pch.hxx.cxx") or f.endswith("cmake_pch.hxx.cpp"):
        continue
    words = shlex.split(e["command"]) if "command" in e else e["arguments"]
    kept, skip = [], False
    for i, w in enumerate(words):
        if skip:
            skip = False
            continue
        if w == "-include" and i + 1 < len(words) and "cmake_pch" in words[i + 1]:
            skip = True
            continue
        if "cmake_pch" in w or w == "-Winvalid-pch":
            continue
        kept.append(w)
    entries.append({"directory": e["directory"], "file": f, "command": shlex.join(kept)})
sources = len(entries)
# The full pass reads a target's batches as one unit: a file in db/ that includes each by its path (a batch's own
# includes are relative to the batch, so they hold). Which batch a source falls in changes as sources come and go,
# so a target's sources compile together whatever the batches; the sources compiled alone need not (the isolation's
# share helpers' names), and stay alone. What changed (--changed) is read unit by unit, as built.
if sys.argv[3] != "--changed":
    groups = {}
    for e in entries:
        if "/batches/" not in e["file"]:
            groups[("", e["file"])] = [e]
            continue
        words = [w for w in shlex.split(e["command"]) if w != e["file"]]
        for flag in ("-o", "-c"):
            while flag in words:
                i = words.index(flag)
                del words[i:i + 2 if flag == "-o" else i + 1]
        groups.setdefault((e["directory"], shlex.join(words)), []).append(e)
    joined = []
    for n, ((directory, flags), members) in enumerate(groups.items()):
        if len(members) == 1:
            joined.append(members[0])
            continue
        unit = os.path.abspath(os.path.join(os.path.dirname(sys.argv[2]), f"unit-{n}.cpp"))
        with open(unit, "w") as f:
            f.write("".join(f'#include "{m["file"]}"\n' for m in members))
        joined.append({"directory": directory, "file": unit, "command": flags + " -c " + shlex.quote(unit)})
    entries = joined
# The batches (simlab_batches), or the targets' joined, each the work of several sources, first: two at a time, the
# pass then ends on short units, not on a batch begun last while the other core waits.
entries.sort(key=lambda e: "/batches/" not in e["file"] and "/db/unit-" not in e["file"])
json.dump(entries, open(sys.argv[2], "w"), indent=1)
print(sources)
PY
)
mapfile -t units < <(python3 -c 'import json,sys; [print(e["file"]) for e in json.load(open(sys.argv[1]))]' db/compile_commands.json)
check "the engine's and the command's translation units are found ($sources, read as ${#units[@]})" test "$sources" -ge 20
if [[ ${1:-} == --changed ]]; then
  base=$(git -C "$SOURCE_DIR" merge-base HEAD main 2>/dev/null || git -C "$SOURCE_DIR" merge-base HEAD origin/main 2>/dev/null ||
         git -C "$SOURCE_DIR" rev-parse HEAD)
  mapfile -t changed < <({ git -C "$SOURCE_DIR" diff --name-only "$base"; git -C "$SOURCE_DIR" ls-files --others --exclude-standard; } |
                         grep -E '\.(cpp|h)$' | sed "s|^|$SOURCE_DIR/|" | sort -u)
  kept=()
  for unit in "${units[@]}"; do
    for file in "${changed[@]}"; do
      # A unit is the source itself, or a batch that includes it (by its path relative to the batch: simlab_batches).
      if [[ $unit == "$file" ]] || grep -qF "\"$(realpath -ms --relative-to="$(dirname "$unit")" "$file")\"" "$unit" 2>/dev/null; then
        kept+=("$unit"); break
      fi
      # A changed header: every unit, as the full pass would.
      [[ $file == *.h ]] && { kept+=("$unit"); break; }
    done
  done
  echo "what changed since $(git -C "$SOURCE_DIR" rev-parse --short "$base"): ${#changed[@]} source(s), ${#kept[@]} unit(s) of ${#units[@]}"
  if [[ ${#kept[@]} -eq 0 ]]; then
    echo "nothing of the engine's or the command's changed"
    finish
  fi
  units=("${kept[@]}")
fi
printf '%s\0' "${units[@]}" |
  xargs -0 -P 2 -n 1 "$tidy" -p db --config-file="$SOURCE_DIR/.clang-tidy" --quiet \
    --extra-arg=-Wno-unknown-warning-option >tidy.out 2>tidy.err
status=$?
check "clang-tidy finds nothing (.clang-tidy's checks, every finding an error)" test "$status" -eq 0
[[ $status -eq 0 ]] || grep -E 'warning:|error:' tidy.out tidy.err | sort -u | head -n 30
finish
