# An installation, moved: the moved simlab grades a file as the build's simlab does, making its precompiled header
# where it now is (once), and a project made by it builds with find_package(simlab) and runs; --version is there;
# an installation makes packages from the sources it carries. In each installed layout - a prefix, the same moved,
# one among the system's files (/usr/local) - the isolation's invariants hold: no code of a submission runs with
# privilege or reads a secret of that installation, with bubblewrap and without. The installation is
# cli/install-tree's ($FIXTURES/install, where cmake --install wrote it and what it wrote is checked), copied: each
# copy is that prefix moved. cmake --install runs here once more, over a copy, as an update does.
# Usage: install.sh BUILD_DIR
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
build=$1
chmod 0755 "$work"  # the prefix is read by the sandbox's throwaway users too
export HOME=$work/home XDG_CACHE_HOME=$work/cache
mkdir -p "$HOME"

installed=$FIXTURES/install
check "cli/install-tree's installation is there to copy" test -x "$installed/bin/simlab"
cp -a "$installed" moved
run_capture version moved/bin/simlab --version
check "the moved simlab says its version" grep -qx "simlab $("$SIMLAB" --version | awk '{ print $2 }')" version.out
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" .
run_capture built "$SIMLAB" check apple NewtonsApple.cpp
run_capture apple moved/bin/simlab check apple NewtonsApple.cpp
check "it grades the apple's solution as the build's simlab does" \
  bash -c "grep -q '^Score: ' apple.out && test \"\$(grep '^Score: ' apple.out)\" = \"\$(grep '^Score: ' built.out)\""
check "making the apple's precompiled header where the prefix now is, and saying so" \
  bash -c "test -f moved/lib/simlab/build/pch/apple.h.pch && grep -q \"making apple's precompiled header\" apple.err"
echo "// edited" >>NewtonsApple.cpp
run_capture again moved/bin/simlab check apple NewtonsApple.cpp
check "once: the next check compiles against it without making it again" \
  bash -c "grep -q '^Score: ' again.out && ! grep -q 'precompiled header' again.err"
check "what it keeps between runs is in the user's cache, not in the prefix" test -d "$XDG_CACHE_HOME/simlab"
# Installed again over itself, the same files: every header is written anew, and the precompiled header is made
# again (clang would take a header whose time changed for another file, and its #pragma once would not hold).
run_capture reinstall cmake --install "$build" --prefix "$work/moved"
run_capture over moved/bin/simlab check apple NewtonsApple.cpp
check "installed again over itself: the precompiled header is made again and the next check grades as before" \
  bash -c "grep -q \"making apple's precompiled header\" over.err &&
    test \"\$(grep '^Score: ' over.out)\" = \"\$(grep '^Score: ' built.out)\""
# Another user of this installation (a TA, as nobody): a grade, or one line saying why, never an abort.
if [[ $(id -u) -eq 0 ]] && command -v setpriv >/dev/null; then
  mkdir -p other && cp NewtonsApple.cpp other/ && chown -R 65534:65534 other
  run_capture other env HOME="$work/other" XDG_CACHE_HOME="$work/other/cache" \
    setpriv --reuid=65534 --regid=65534 --clear-groups moved/bin/simlab check apple other/NewtonsApple.cpp
  sed 's/^/    /' other.err | tail -2
  check "another user of the installation gets a grade or one line saying why, never an abort" \
    bash -c "test $(status_of other) -ne 134 && ! grep -q 'terminate called' other.err &&
      { grep -q '^Score: ' other.out || test \$(grep -c '^simlab: error: ' other.err) -eq 1; }"
  check "  which, where the judges are closed to them, says whose they are and what to do" \
    bash -c "grep '^Score: ' other.out || grep -q \"apple's judge .* is for $(id -un) alone to read: .*check and grade as $(id -un)\" other.err"
  mkdir -p other/class/ada && cp NewtonsApple.cpp other/class/ada/ && chown -R 65534:65534 other
  run_capture other-grade env HOME="$work/other" XDG_CACHE_HOME="$work/other/cache" \
    setpriv --reuid=65534 --regid=65534 --clear-groups moved/bin/simlab grade apple other/class -o other/grades
  check "and so does simlab grade: a class graded, or one line saying why" \
    bash -c "test $(status_of other-grade) -ne 134 && ! grep -q 'terminate called' other-grade.err &&
      { grep -q '^1 graded' other-grade.out || test \$(grep -c '^simlab: error: ' other-grade.err) -eq 1; }"
fi

# invariants LAYOUT MANIFEST: the isolation's invariants graded by that installation, with bubblewrap and without,
# its files opened to every user first: the sandbox hides them, not their modes (which the installer closes too).
# The random system calls have a test of their own in each mode (cli/random-calls); here, each entry point and the
# walk from a test's call.
invariants() {
  local layout=$1 manifest=$2 mode cases=()
  for c in "$SOURCE_DIR"/tests/corpus/apple/invariants/*.toml; do
    [[ $c == */random-calls.toml ]] || cases+=("$c")
  done
  chmod -R o+rX "$(dirname "$manifest")" "$(dirname "$(dirname "$(dirname "$manifest")")")/share/simlab"
  for mode in bubblewrap Landlock; do
    local settings=(SIMLAB_MANIFEST="$manifest")
    [[ $mode == Landlock ]] && settings+=(SIMLAB_NO_BUBBLEWRAP=1)
    run_capture "invariants-$layout-$mode" env "${settings[@]}" "$CORPUS" invariants apple "${cases[@]}"
    if [[ $mode == Landlock ]] && ! grep -q '^sandbox: Landlock' "invariants-$layout-$mode.out"; then
      echo "skipped: the invariants of the $layout installation without bubblewrap (no Landlock here)"
      continue
    fi
    grep -E '^(OK|FAILED|    )' "invariants-$layout-$mode.out" | sed 's/^/    /'
    check "installed ($layout, $mode): no code of a submission ran with privilege or read a secret of the installation" \
      bash -c "test $(status_of "invariants-$layout-$mode") -eq 0 && grep -q '^manifest: $manifest' invariants-$layout-$mode.out"
  done
}
invariants moved "$work/moved/lib/simlab/simlab-build.json"

# Where files are kept apart by their modes alone (no bubblewrap, no Landlock), an installation closed by simlab lock
# runs hidden tests, and the walk finds nothing of it a test may not read; open, simlab refuses them.
moved_manifest=$work/moved/lib/simlab/simlab-build.json
walk=$SOURCE_DIR/tests/corpus/apple/invariants/reach-walk.toml
limits=(SIMLAB_NO_BUBBLEWRAP=1 SIMLAB_NO_LANDLOCK=1)
run_capture open-limits env SIMLAB_MANIFEST="$moved_manifest" "${limits[@]}" "$CORPUS" invariants apple "$walk"
check "installed, open to all, limits only: simlab refuses hidden tests, naming a file of it and simlab lock" \
  grep -qE "^limits only: simlab refuses hidden tests here: .* could read $work/.* close them with .simlab lock" open-limits.out
run_capture lock env SIMLAB_MANIFEST="$moved_manifest" moved/bin/simlab lock
check "simlab lock closes the installation but what a test's tools are lent" \
  grep -qE '^simlab lock: [0-9]+ files and folders closed to other users .*; [1-9][0-9]* left to the tools as lent' lock.out
run_capture locked-limits env SIMLAB_MANIFEST="$moved_manifest" "${limits[@]}" "$CORPUS" invariants apple "$walk"
grep -E '^(limits only|OK|FAILED|    )' locked-limits.out | sed 's/^/    /'
check "closed, limits only: the walk reads nothing of the installation a test may not read, and hidden tests run" \
  bash -c "test $(status_of locked-limits) -eq 0 && grep -q '^limits only: nothing of simlab.s places opens' locked-limits.out &&
    grep -qE 'walk: [1-9][0-9]* folders listed, [1-9][0-9]* files readable, 0 outside' locked-limits.out"
run_capture locked-all env "${limits[@]}" moved/bin/simlab check apple NewtonsApple.cpp --all
check "and simlab check --all grades every test there" grep -q '^Score: ' locked-all.out

# A lab of one's own with a history of its own, graded by the installation: among the system's files where this user
# may write there (/usr/local/share, which every sandbox lets its processes read), else beside it. The walk, in each
# mode, reads nothing of it - its history, its solution, its build - that a test may not read.
labs=$work/labs
[[ -w /usr/local/share ]] && labs=/usr/local/share/simlab-lab-test-$$
trap 'rm -rf "$work" "${system:-}" "$labs"' EXIT
mkdir -p "$labs" && chmod 0755 "$labs" && cp -r "$SOURCE_DIR/examples/pendulum" "$labs/"
(cd "$labs/pendulum" && git init -q && git add -A && git -c user.name=author -c user.email=author@example.edu commit -qm lab)
chmod -R go-rwx "$labs/pendulum/grading/hidden.cpp" "$labs/pendulum/solution" "$labs/pendulum/corpus"
lab_walk=$SOURCE_DIR/tests/corpus/pendulum/invariants/reach-walk.toml
for mode in bubblewrap Landlock "limits only"; do
  settings=(SIMLAB_MANIFEST="$moved_manifest")
  [[ $mode == Landlock ]] && settings+=(SIMLAB_NO_BUBBLEWRAP=1)
  [[ $mode == "limits only" ]] && settings+=("${limits[@]}")
  name=lab-${mode// /-}
  if [[ $mode == "limits only" ]]; then
    run_capture "$name-lock" env "${settings[@]}" moved/bin/simlab lock "$labs/pendulum"
  fi
  run_capture "$name" env "${settings[@]}" "$CORPUS" invariants "$labs/pendulum" "$lab_walk"
  if ! grep -q "^sandbox: $mode" "$name.out"; then
    echo "skipped: the lab's walk in $mode (not this machine's: $(grep -m1 '^sandbox' "$name.out"))"
    continue
  fi
  grep -E '^(limits only|OK|FAILED|    )' "$name.out" | sed 's/^/    /'
  check "installed, a lab of one's own with its history in $labs ($mode): the walk reads nothing a test may not read" \
    bash -c "test $(status_of "$name") -eq 0 && grep -qE 'walk: [1-9][0-9]* folders listed, [1-9][0-9]* files readable, 0 outside' $name.out"
done
chmod -R o+rX "$work/moved"  # open again for what follows

run_capture new moved/bin/simlab project new myboot --from babyboot
check "a project made by the installed simlab asks for it with find_package(simlab)" \
  grep -q "^find_package(simlab .* REQUIRED CONFIG HINTS \"$work/moved/lib/cmake/simlab\")$" myboot/CMakeLists.txt
(cmake -S myboot -B myboot/build >cmake.log 2>&1 && cmake --build myboot/build >>cmake.log 2>&1)
check "and builds against it with CMake" test -x myboot/build/myboot || tail -20 cmake.log
run_capture myboot myboot/build/myboot --quiet --final-time 1
check "and runs as its own lab program" grep -q '^myboot: A swinging baby boot' myboot.out
run_capture bootversion myboot/build/myboot --version
check "which says its version" grep -q '^myboot (simlab ' bootversion.out

# Installed among the system's files (/usr/local), which every sandbox lets its processes read: the hidden tests,
# solutions and judges are there for the installing user alone, and a file that includes one is refused it, with
# bubblewrap and without (Landlock and a user of its own, as in Gradescope's and PrairieLearn's containers).
if [[ -w /usr/local ]]; then
  system=/usr/local/simlab-install-test-$$
  trap 'rm -rf "$work" "$system" "$labs"' EXIT
  cp -a "$installed" "$system"
  cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" solution.cpp
  for secret in share/simlab/source/assignments/apple/grading/hidden.cpp lib/simlab/build/judges/apple-judge \
                share/simlab/source/solutions/apple/NewtonsApple.cpp; do
    name=$(basename "$secret")
    mkdir -p "reads-$name"
    { echo "#include \"$system/$secret\""; cat solution.cpp; } >"reads-$name/NewtonsApple.cpp"
    for mode in bubblewrap none; do
      if [[ $mode == none ]]; then export SIMLAB_NO_BUBBLEWRAP=1; else unset SIMLAB_NO_BUBBLEWRAP; fi
      run_capture "reads-$name-$mode" "$system/bin/simlab" check apple "reads-$name/NewtonsApple.cpp"
      check "installed in /usr/local ($mode): a file that includes $secret is refused it" \
        bash -c "grep -q \"'$system/$secret' file not found\" reads-$name-$mode.out && grep -qx 'Score: 0/76' reads-$name-$mode.out"
    done
  done
  unset SIMLAB_NO_BUBBLEWRAP
  run_capture systemall env SIMLAB_NO_BUBBLEWRAP=1 "$system/bin/simlab" check apple solution.cpp --all
  check "and the hidden tests run there without bubblewrap, out of the tests' reach" grep -qx 'Score: 100/100' systemall.out
  invariants usr-local "$system/lib/simlab/simlab-build.json"
fi

# An installation carries the project's sources: it makes packages as a build does, without its secrets.
run_capture package moved/bin/simlab package gradescope apple -o apple.zip
unzip -Z1 apple.zip >zipped.txt 2>/dev/null
check "the installed simlab makes a Gradescope package from the sources it carries" \
  bash -c "test $(status_of package) -eq 0 && grep -qx scripts/setup zipped.txt && grep -qx CMakeLists.txt zipped.txt &&
    grep -qx assignments/apple/grading/hidden.cpp zipped.txt"
check "with no solution, test or example lab in it" \
  bash -c "! grep -E '^(solutions/[^b]|tests/|examples/)' zipped.txt"
check "and none of the course's other labs: their hidden tests and trade files are not the apple's autograder's" \
  bash -c "! grep -E '^(assignments|starter)/(projectile|book|biosim)/' zipped.txt"
finish
