# The editor's side of the dev container, as VS Code would use it: devcontainer.json, .vscode/tasks.json and
# .vscode/launch.json are read as JSON; each starter is a translation unit of the build's compile_commands.json whose
# headers are found; the check task's problem matchers, applied to simlab check's real output, take the student to
# the TODO's line, to a compile error's line and to the line a crash, an exception or an endless loop was at in their
# own file; the plot, replay and run tasks work as written; and the launch configuration's program stops at a
# breakpoint in the student's file under gdb.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

build=$(cd "$BIN_DIR/.." && pwd)
check "devcontainer.json, tasks.json and launch.json are JSON" \
  python3 -c 'import json,sys; [json.load(open(f)) for f in sys.argv[1:]]' "$SOURCE_DIR/.devcontainer/devcontainer.json" \
  "$SOURCE_DIR/.vscode/tasks.json" "$SOURCE_DIR/.vscode/launch.json"
check "the dev container builds the folder on create, with VS Code's C/C++ and CMake tools" python3 - "$SOURCE_DIR" <<'PY'
import json, sys
d = json.load(open(sys.argv[1] + "/.devcontainer/devcontainer.json"))
ext = d["customizations"]["vscode"]["extensions"]
assert d["onCreateCommand"] == "scripts/setup --no-test-tools", d["onCreateCommand"]
assert "ms-vscode.cpptools" in ext and "ms-vscode.cmake-tools" in ext, ext
assert d["customizations"]["vscode"]["settings"]["C_Cpp.default.compileCommands"] == \
    "${workspaceFolder}/build/compile_commands.json"
assert d["build"]["context"] == ".." and d["build"]["dockerfile"] == "Dockerfile"
PY

check "every program the tasks and the launch configuration offer is a target of the build" python3 - "$SOURCE_DIR" "$build" <<'PY'
import json, subprocess, sys
targets = set(l[4:] for l in subprocess.run(["cmake", "--build", sys.argv[2], "--target", "help"],
                                           capture_output=True, text=True).stdout.splitlines() if l.startswith("... "))
for name in ("tasks.json", "launch.json"):
    for i in json.load(open(sys.argv[1] + "/.vscode/" + name))["inputs"]:
        if i["id"] == "program":
            missing = set(i["options"]) - targets
            assert not missing, (name, missing)
PY

# Each starter in compile_commands.json, its headers found with the command written there.
python3 - "$build/compile_commands.json" "$SOURCE_DIR" >units.txt <<'PY'
import json, shlex, sys
for e in json.load(open(sys.argv[1])):
    if e["file"].startswith(sys.argv[2] + "/starter/"):
        words = shlex.split(e["command"]) if "command" in e else e["arguments"]
        if "-o" in words:
            i = words.index("-o")
            del words[i:i + 2]
        print(e["directory"] + "\t" + shlex.join(words + ["-fsyntax-only"]))
PY
check "compile_commands.json lists the four starters" test "$(wc -l <units.txt)" -eq 4
while IFS=$'\t' read -r directory command; do
  check "  $(basename "${command%% -fsyntax-only}" | awk '{print $NF}') compiles there (its headers found)" \
    bash -c "cd '$directory' && $command"
done <units.txt

# The check task's problem matchers on simlab check's output, in a workspace of the student's: the starter with
# its first TODO, then with a compile error. VS Code's "search" location: the file of that name under the folders.
mkdir -p ws/starter/apple
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" ws/starter/apple/
todo_line=$(grep -n '^ *SIMLAB_TODO(' ws/starter/apple/NewtonsApple.cpp | head -1 | cut -d: -f1)
matched() {  # matched OUTPUT: each problem the check task's matchers find, as file:line: message
  python3 - "$SOURCE_DIR/.vscode/tasks.json" "$PWD/ws" "$1" <<'PY'
import json, os, re, sys
tasks = json.load(open(sys.argv[1]))["tasks"]
task = next(t for t in tasks if t["label"] == "simlab: check")
for line in open(sys.argv[3]).read().splitlines():
    for m in task["problemMatcher"]:
        p = m["pattern"]
        found = re.match(p["regexp"], line)
        if not found:
            continue
        kind, where = m["fileLocation"]
        folders = [f.replace("${workspaceFolder}", sys.argv[2]) for f in where["include"]]
        hits = [os.path.join(r, found.group(p["file"])) for f in folders if os.path.isdir(f)
                for r, _, files in os.walk(f) if found.group(p["file"]) in files]
        print(f'{os.path.relpath(hits[0], sys.argv[2]) if hits else "?"}:{found.group(p["line"])}: '
              f'{found.group(p["message"])}')
PY
}
(cd ws && "$SIMLAB" check apple starter/apple/NewtonsApple.cpp >../todo.out 2>&1)
matched todo.out >todo.problems
check "a TODO left is a problem at its line in the student's file" \
  grep -q "^starter/apple/NewtonsApple.cpp:$todo_line: build the model" todo.problems
awk 'NR==45{print "int broken = ;"}1' "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" >ws/starter/apple/NewtonsApple.cpp
(cd ws && "$SIMLAB" check apple starter/apple/NewtonsApple.cpp >../broken.out 2>&1)
matched broken.out >broken.problems
check "a compile error is a problem at its line and column's line" \
  grep -q "^starter/apple/NewtonsApple.cpp:45: expected expression" broken.problems

# A crash, an exception and an endless loop in the student's file are problems at their lines, each once: the
# reference solution with one bug, on one test (the loop stopped after a second of CPU time).
bug() {  # bug NAME FIND REPLACE [CHECK OPTIONS...]: NAME.line is the bug's line, NAME.problems what the matchers find
  local name=$1 find=$2 replace=$3
  shift 3
  python3 - "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" "$find" "$replace" >ws/starter/apple/NewtonsApple.cpp <<'PY'
import sys
text = open(sys.argv[1]).read()
assert text.count(sys.argv[2]) == 1, sys.argv[2]
sys.stdout.write(text.replace(sys.argv[2], sys.argv[3] + "  // the bug\n" + sys.argv[2]))
PY
  grep -n '// the bug$' ws/starter/apple/NewtonsApple.cpp | cut -d: -f1 >"$name.line"
  (cd ws && "$SIMLAB" check apple starter/apple/NewtonsApple.cpp --test "the apple starts at rest at the drop height" \
     "$@" >"../$name.out" 2>&1)
  matched "$name.out" >"$name.problems"
}
bug crash "    // Energies need forces" "    *static_cast<volatile int*>(nullptr) = 1;"
check "a crash is a problem at its line, once" \
  grep -qx "starter/apple/NewtonsApple.cpp:$(cat crash.line): crashed (SIGSEGV) in apple::sample() (NewtonsApple.cpp:$(cat crash.line)): a bad pointer, or a stack overflowed by endless recursion" crash.problems
bug exception "    TimeStepper stepper" "    throw std::runtime_error(\"my bug\");"
check "an exception is a problem at the line that threw it" \
  grep -qx "starter/apple/NewtonsApple.cpp:$(cat exception.line): threw std::runtime_error in apple::simulate() (NewtonsApple.cpp:$(cat exception.line)): my bug" exception.problems
bug loop "    TimeStepper stepper" "    for (volatile double x = 1; x > 0;) x = x * 1.0000001;" --timeout 1
check "an endless loop is a problem at the line it was stopped in" \
  grep -qx "starter/apple/NewtonsApple.cpp:$(cat loop.line): stopped in apple::simulate() (NewtonsApple.cpp:$(cat loop.line)): no end within 1 s of CPU time" loop.problems
check "  and each of them once" bash -c "test \$(cat crash.problems exception.problems loop.problems | wc -l) -eq 3"

# The run, plot and replay tasks as written, in a workspace whose build is the one under test: on the starter the
# run stops at its TODO, which the run task's matcher finds; plot and replay are run on the finished file's program.
rm -rf ws && mkdir ws && ln -s "$build" ws/build
task_command() {  # task_command LABEL PROGRAM
  python3 - "$SOURCE_DIR/.vscode/tasks.json" "$1" "$2" <<'PY'
import json, sys
t = next(t for t in json.load(open(sys.argv[1]))["tasks"] if t["label"] == sys.argv[2])
# The build step is the build under test's, already made: the program's own part alone is run.
print(t["command"].split(" && ", 1)[-1].replace("${input:program}", sys.argv[3]))
PY
}
for task in "simlab: plot" "simlab: replay"; do
  (cd ws && bash -c "$(task_command "$task" apple-reference)") >task.out 2>&1
  check "the task '$task' runs as written" test $? -eq 0
done
check "  and makes its file" test -s ws/apple-reference.svg -a -s ws/apple-reference-replay.html
(cd ws && bash -c "$(task_command "simlab: run the lab program" apple)") >run.out 2>&1
check "the run task's matcher finds the starter's TODO in what the program says" python3 - "$SOURCE_DIR/.vscode/tasks.json" run.out <<'PY'
import json, re, sys
t = next(t for t in json.load(open(sys.argv[1]))["tasks"] if t["label"] == "simlab: run the lab program")
assert any(re.match(t["problemMatcher"]["pattern"]["regexp"], l) for l in open(sys.argv[2]).read().splitlines())
PY

# The launch configuration: its program under gdb stops in the student's file (the lab program's object has line
# tables; the graded object does not need them).
program=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["configurations"][0]["program"])' \
  "$SOURCE_DIR/.vscode/launch.json")
program=${program//\$\{workspaceFolder\}/$PWD/ws}
program=${program//\$\{input:program\}/apple}
if command -v gdb >/dev/null; then
  (cd ws && gdb -batch -ex "break NewtonsApple.cpp:$todo_line" -ex run "$program" </dev/null >../gdb.out 2>&1)
  check "the launch configuration's program stops at a breakpoint on the TODO's line" \
    grep -q "hit Breakpoint 1, apple::buildModel .*NewtonsApple.cpp:$todo_line" gdb.out
else
  echo "skipped: no gdb"
fi
finish
