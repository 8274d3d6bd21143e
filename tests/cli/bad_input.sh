# Bad input to every command: a one-line error on stderr, a non-zero status, nothing on stdout, no hang.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

expect_error() {  # expect_error DESCRIPTION PATTERN COMMAND...
  local what=$1 pattern=$2; shift 2
  timeout 60 "$@" >err.out 2>err.err </dev/null
  local status=$?
  if [[ $status -eq 0 || $status -eq 124 ]]; then fail "$what: status $status"; return; fi
  if [[ $(wc -l <err.err) -ne 1 ]]; then fail "$what: stderr is not one line:"; cat err.err; return; fi
  if ! grep -qE "$pattern" err.err; then fail "$what: stderr does not match '$pattern':"; cat err.err; return; fi
  if [[ -s err.out ]]; then fail "$what: printed on stdout"; return; fi
  pass "$what ($(cat err.err))"
}

echo 'int main() {}' >notes.txt
mkdir folder
expect_error "unknown assignment" "unknown assignment 'pear'; available: apple, projectile, book" "$SIMLAB" check pear
expect_error "missing source file" "source file 'nope.cpp' does not exist" "$SIMLAB" check apple nope.cpp
expect_error "non-C++ file" "is not a C\+\+ source file" "$SIMLAB" check apple notes.txt
expect_error "a directory" "is a directory" "$SIMLAB" check apple folder
expect_error "bad --format" "format" "$SIMLAB" check apple --format xml
expect_error "bad --timeout" "timeout: must be between 0.1 and 3600 s, got -3" "$SIMLAB" check apple --timeout -3
# Limits out of range once zeroed every test silently; now each is a one-line error.
expect_error "a timeout of 1e10 s" "timeout: must be between 0.1 and 3600 s, got 1e\\+10" "$SIMLAB" check apple --timeout 1e10
expect_error "grade: a memory of 1e30 MiB" "memory: must be between 64 and 65536 MiB, got 1e\\+30" \
  "$SIMLAB" grade apple --memory 1e30
expect_error "grade: --timeout nan" "timeout: must be a number, got nan" "$SIMLAB" grade apple --timeout nan
expect_error "grade: no jobs" "jobs" "$SIMLAB" grade apple --jobs 0
expect_error "grade: 65 jobs" "jobs" "$SIMLAB" grade apple --jobs 65
expect_error "a rubric with a limit out of range" "cpu_seconds must be between 0.1 and 3600 s, got 1e\+10" \
  bash -c "sed 's/^cpu_seconds = 5 /cpu_seconds = 1e10/' '$SOURCE_DIR/assignments/apple/grading/rubric.toml' >far.toml && '$SIMLAB' check apple --rubric far.toml"
# A file to check is read as grading reads it: a link, a pipe or a huge file is refused in one line.
ln -s /etc/shadow Linked.cpp
expect_error "a source that is a symbolic link" "Linked.cpp is a symbolic link; hand in the file itself" \
  "$SIMLAB" check apple Linked.cpp
mkfifo Piped.cpp
expect_error "a source that is a named pipe" "Piped.cpp is a named pipe" "$SIMLAB" check apple Piped.cpp
truncate -s 3G Huge.cpp
expect_error "a source of 3 GiB" "Huge.cpp is 3.0 GiB; the limit is 1.0 MiB" "$SIMLAB" check apple Huge.cpp
expect_error "no subcommand" "subcommand" "$SIMLAB"
expect_error "unknown command" "unknown command 'frobnicate'; commands: check" "$SIMLAB" frobnicate
expect_error "grade: missing folder" "no submissions folder" "$SIMLAB" grade apple no-such-folder
expect_error "build: unknown assignment" "unknown assignment" "$SIMLAB" build pear
expect_error "build: output in a missing folder" "no directory" "$SIMLAB" build apple -o no/such/dir/apple
expect_error "rubric with a syntax error" "error in the rubric: .*bad.toml:1:" \
  bash -c "echo 'assignment = ' >bad.toml && '$SIMLAB' check apple --rubric bad.toml"
expect_error "apple: unknown integrator" "unknown integrator 'Euler'; choose one of: RungeKuttaMerson" \
  "$BIN_DIR/apple-reference" --integrator Euler
expect_error "apple: negative dt" "dt: must be a positive number, got -1" "$BIN_DIR/apple-reference" --dt -1
# A range's limits as written: 1e-15, not CLI11's six decimals ("0.000000").
expect_error "apple: an accuracy below the range" "accuracy: must be between 1e-15 and 0.5, got 1e-20" \
  "$BIN_DIR/apple-reference" --accuracy 1e-20
expect_error "apple: a negative gravity" "gravity: must be between 0 and 10000, got -1" \
  "$BIN_DIR/apple-reference" --gravity -1
expect_error "apple: dt beyond the final time" "dt must not exceed the final time" \
  "$BIN_DIR/apple-reference" --dt 5 --final-time 4 --quiet
expect_error "apple: results file in a missing folder" "cannot write results file" \
  "$BIN_DIR/apple-reference" --output no/such/dir/results.txt
expect_error "projectile: angle beyond 90 degrees" "angle: must be in \(0, 90\] degrees, got 95" \
  "$BIN_DIR/projectile-reference" --angle 95
expect_error "projectile: angle of 0" "must be in \(0, 90\] degrees, got 0" "$BIN_DIR/projectile-reference" --angle 0
expect_error "projectile: negative speed" "speed: must be a positive number, got -3" \
  "$BIN_DIR/projectile-reference" --speed -3
expect_error "projectile: no gravity" "gravity: must be a positive number, got 0" \
  "$BIN_DIR/projectile-reference" --gravity 0
expect_error "book: unknown spin" "spin: sideways not in" "$BIN_DIR/book-reference" --spin sideways
expect_error "book: --spin with --omega" "excludes" "$BIN_DIR/book-reference" --spin min --omega 1,2,3
expect_error "book: two components" "omega" "$BIN_DIR/book-reference" --omega 1,2
expect_error "book: a negative dimension" "dimensions: must be a positive number, got -0.3" \
  "$BIN_DIR/book-reference" --dimensions 0.2,-0.3,0.05
# A header the precompiled one was made from changed since the build (a package upgrade): the compiler would refuse
# every file that includes it again, so simlab stops in one line before compiling anything, and says how to rebuild.
# A build whose record of that header's bytes no longer matches them, as such an upgrade leaves it:
python3 - "$BIN_DIR/../simlab-build.json" "$work" <<'PY'
import json, os, sys, time
manifest, work = json.load(open(sys.argv[1])), sys.argv[2]
compile = [a for a in manifest["assignments"] if a["id"] == "apple"][0]["compile"]
for i, flag in enumerate(compile[:-1]):
    if flag in ("-include-pch", "-include"):
        real = compile[i + 1] + (".gch" if flag == "-include" else "")
        os.symlink(real, work + "/course.pch")
        compile[i + 1] = work + "/course.pch" if flag == "-include-pch" else work + "/course"
        if flag == "-include":
            os.symlink(real, work + "/course.gch")
pch = work + ("/course.pch" if "-include-pch" in compile else "/course.gch")
with open(pch + ".inputs", "w") as record:
    record.write("0" * 64 + " " + work + "/upgraded.h\n")
past = time.time() - 3600
os.utime(pch + ".inputs", (past, past))
with open(work + "/upgraded.h", "w") as header:
    header.write("// new bytes\n")
json.dump(manifest, open(work + "/manifest.json", "w"))
PY
echo 'int x;' >Upgraded.cpp
expect_error "a system header changed since simlab was built" \
  "upgraded.h has changed since simlab was built \(a package upgrade\?\).*rebuild simlab \(cmake --build" \
  env SIMLAB_MANIFEST="$work/manifest.json" "$SIMLAB" check apple Upgraded.cpp
if [[ $(id -u) -ne 0 ]]; then
  echo 'int x;' >locked.cpp && chmod 000 locked.cpp
  expect_error "unreadable source" "locked.cpp cannot be read" "$SIMLAB" check apple locked.cpp
fi
finish
