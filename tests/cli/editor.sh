# The editor's side of the dev container, as VS Code would use it: devcontainer.json, .vscode/tasks.json and
# .vscode/launch.json are read as JSON; each starter is a translation unit of the build's compile_commands.json whose
# headers are found. The tasks and the launch configuration act on the file open in the editor: each is resolved as
# VS Code resolves it (${file}, ${fileDirname}, ${workspaceFolder}) and run as written, in a workspace shaped like
# the simlab folder, on a lab's starter and on projects of the student's own that `simlab project new` made there.
# Their problem matchers, applied to the real output, take the student to the TODO's line and to a compile error's
# line in the very file open (a project's Project.cpp, not the template's), and to the line a crash, an exception or
# an endless loop was at in the student's own file; the build, run, plot and replay tasks
# work; and the launch configuration's program stops at a breakpoint in the student's file under gdb.
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

check "every task acts on the file open in the editor, through scripts/editor-task; the debugger on what it built" \
  python3 - "$SOURCE_DIR" <<'PY'
import json, sys
tasks = json.load(open(sys.argv[1] + "/.vscode/tasks.json"))["tasks"]
for t in tasks:
    assert t["command"].startswith("scripts/editor-task ") and t["command"].endswith(' "${file}"'), t["command"]
launch = json.load(open(sys.argv[1] + "/.vscode/launch.json"))["configurations"][0]
assert launch["program"] == "${workspaceFolder}/build/editor/program", launch["program"]
assert launch["cwd"] == "${workspaceFolder}/build/editor/cwd", launch["cwd"]
assert launch["preLaunchTask"] in [t["label"] for t in tasks], launch["preLaunchTask"]
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

# A workspace shaped like the simlab folder: its scripts are this tree's and its build the one under test. A lab's
# student file is open in starter/LAB/; the template's Project.cpp lies in starter/biosim/, where a search that
# ignored the open folder would find it first.
mkdir -p ws/starter/apple ws/starter/biosim
ln -s "$SOURCE_DIR/scripts" ws/scripts
ln -s "$build" ws/build
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" ws/starter/apple/
cp "$SOURCE_DIR/starter/biosim/Project.cpp" "$SOURCE_DIR/starter/biosim/project.toml" ws/starter/biosim/
ws=$PWD/ws
task() {  # task LABEL FILE: the task run as VS Code runs it with FILE open in the editor; its output on stdout
  python3 - "$SOURCE_DIR/.vscode/tasks.json" "$1" "$ws" "$2" <<'PY'
import json, os, subprocess, sys
t = next(t for t in json.load(open(sys.argv[1]))["tasks"] if t["label"] == sys.argv[2])
ws, file = sys.argv[3], os.path.abspath(sys.argv[4])
def resolve(text):
    return text.replace("${workspaceFolder}", ws).replace("${fileDirname}", os.path.dirname(file)).replace("${file}", file)
cwd = resolve(t.get("options", {}).get("cwd", "${workspaceFolder}"))
sys.exit(subprocess.run(["bash", "-c", resolve(t["command"])], cwd=cwd, stderr=subprocess.STDOUT).returncode)
PY
}
matched() {  # matched LABEL OUTPUT FILE: each problem the task's matchers find in OUTPUT, with FILE open in the editor
  python3 - "$SOURCE_DIR/.vscode/tasks.json" "$1" "$2" "$ws" "$3" <<'PY'
import json, os, re, sys
t = next(t for t in json.load(open(sys.argv[1]))["tasks"] if t["label"] == sys.argv[2])
ws, file = sys.argv[4], os.path.abspath(sys.argv[5])
matchers = t["problemMatcher"] if isinstance(t["problemMatcher"], list) else [t["problemMatcher"]]
for line in open(sys.argv[3], errors="replace").read().splitlines():
    for m in matchers:
        p = m["pattern"]
        found = re.match(p["regexp"], line)
        if not found:
            continue
        # VS Code's "search" location: the first file of that name under the folders, taken in order.
        kind, where = m["fileLocation"]
        assert kind == "search", kind
        name, hit = found.group(p["file"]), None
        for folder in where["include"]:
            folder = folder.replace("${workspaceFolder}", ws).replace("${fileDirname}", os.path.dirname(file))
            for root, _, files in os.walk(folder):
                if hit is None and name in files:
                    hit = os.path.join(root, name)
            if hit:
                break
        print(f'{os.path.relpath(hit, ws) if hit else "?"}:{found.group(p["line"])}: {found.group(p["message"])}')
PY
}

# A lab: its starter open in the editor, with its first TODO, then with a compile error.
todo_line=$(grep -n '^ *SIMLAB_TODO(' ws/starter/apple/NewtonsApple.cpp | head -1 | cut -d: -f1)
task "simlab: check" ws/starter/apple/NewtonsApple.cpp >todo.out
check "the check task on a lab's starter checks it: 0/76" grep -q '^Score: 0/76$' todo.out
matched "simlab: check" todo.out ws/starter/apple/NewtonsApple.cpp >todo.problems
check "  a TODO left is a problem at its line in the student's file" \
  grep -q "^starter/apple/NewtonsApple.cpp:$todo_line: build the model" todo.problems
awk 'NR==45{print "int broken = ;"}1' "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" >ws/starter/apple/NewtonsApple.cpp
task "simlab: check" ws/starter/apple/NewtonsApple.cpp >broken.out
matched "simlab: check" broken.out ws/starter/apple/NewtonsApple.cpp >broken.problems
check "  a compile error is a problem at its line" \
  grep -q "^starter/apple/NewtonsApple.cpp:45: expected expression" broken.problems
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" ws/starter/apple/
# The lab program of the build under test is built from the tree's starter: the task rebuilds nothing.
task "simlab: run the lab program" ws/starter/apple/NewtonsApple.cpp >run.out
matched "simlab: run the lab program" run.out ws/starter/apple/NewtonsApple.cpp >run.problems
check "the run task on a lab's starter builds its program alone and runs it to its TODO, a problem at its line" \
  bash -c "grep -q 'Built target apple' run.out && ! grep -q 'Built target simlab\$' run.out &&
           grep -q '^starter/apple/NewtonsApple.cpp:$todo_line: build the model' run.problems"

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
  matched "simlab: check" "$name.out" ws/starter/apple/NewtonsApple.cpp >"$name.problems"
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

cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" ws/starter/apple/

# A project of the student's own, made as the handout makes it (simlab project new, from the top of the folder):
# its check, build and run tasks act on it, not on the template in starter/biosim.
(cd ws && build/bin/simlab project new dpend >/dev/null)
project_todo=$(grep -n '^ *SIMLAB_TODO(' ws/dpend/Project.cpp | head -1 | cut -d: -f1)
task "simlab: check" ws/dpend/Project.cpp >project-check.out
check "the check task on a project's file checks the project" \
  bash -c "grep -q '^Biosimulation project (biosim): $ws/dpend/Project.cpp' project-check.out && grep -q '^Score: 0/75$' project-check.out"
matched "simlab: check" project-check.out ws/dpend/Project.cpp >project-check.problems
check "  its problems are in the project's own Project.cpp" \
  bash -c "test -s project-check.problems && ! grep -v '^dpend/Project.cpp:' project-check.problems"
task "simlab: run the lab program" ws/dpend/Project.cpp >project-run.out
matched "simlab: run the lab program" project-run.out ws/dpend/Project.cpp >project-run.problems
check "the run task builds the project's own program, ./build/dpend, and runs it to its TODO, a problem there" \
  bash -c "test -x ws/dpend/build/dpend && grep -q '^dpend: not done yet (Project.cpp:$project_todo)' project-run.out &&
           grep -q '^dpend/Project.cpp:$project_todo: ' project-run.problems"

# A finished project (the worked example, copied): the plot and replay tasks draw its run in its folder, and the
# launch configuration's program stops at a breakpoint in its Project.cpp (the program carries line tables; the
# graded object does not need them).
(cd ws && build/bin/simlab project new boot --from babyboot >/dev/null)
for action in plot replay; do
  task "simlab: $action" ws/boot/Project.cpp >"$action.out"
  check "the $action task on a finished project's file draws its run" test $? -eq 0
done
check "  in the project's folder" test -s ws/boot/boot.svg -a -s ws/boot/boot-replay.html
task "simlab: build for the debugger" ws/boot/Project.cpp >debug.out
program=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["configurations"][0]["program"])' \
  "$SOURCE_DIR/.vscode/launch.json")
program=${program//\$\{workspaceFolder\}/$ws}
check "the launch configuration's program is the open project's, run in its folder" \
  bash -c "test \"\$(readlink -f '$program')\" = \"\$(readlink -f ws/boot/build/boot)\" &&
           test \"\$(readlink -f ws/build/editor/cwd)\" = \"\$(readlink -f ws/boot)\""
line=$(grep -n 'MobilizedBody::Pin' ws/boot/Project.cpp | head -1 | cut -d: -f1)
if command -v gdb >/dev/null; then
  (cd ws/build/editor/cwd && gdb -batch -ex "break Project.cpp:$line" -ex run "$program" </dev/null >"$OLDPWD/gdb.out" 2>&1)
  check "  and stops at a breakpoint in its Project.cpp" grep -q "hit Breakpoint 1, .*Project.cpp:$line" gdb.out
else
  echo "skipped: no gdb"
fi
rm -f "$build/editor/program" "$build/editor/cwd"  # they point into this test's workspace

task "simlab: check" "$SOURCE_DIR/README.md" >nowhere.out
nowhere=$?
check "a file in no lab's or project's folder is one line saying so, exit 2" \
  bash -c "test $nowhere -eq 2 && test \$(wc -l <nowhere.out) -eq 1 && grep -q 'in no lab.s folder' nowhere.out"
finish
