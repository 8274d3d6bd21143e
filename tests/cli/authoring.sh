# A lab of one's own, as an instructor makes it: simlab installed with cmake --install (a copy of cli/install-tree's
# installation, $FIXTURES/install), the example lab
# (examples/pendulum) copied out of the tree, and every command given its folder. The installed simlab builds it
# against its CMake package on first use; `assignment verify` exits 0 (reference full, starter low, each corpus
# case its score, no hidden file in the students' copy); a class of the reference and the starter is graded; the
# Gradescope package carries the lab with its hidden tests and without its solution and corpus, and its setup
# builds it. A broken copy makes verify fail, one line per check.
# Usage: authoring.sh
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
chmod 0755 "$work"  # without bubblewrap, the sandbox's throwaway users read the prefix and the lab's build
export HOME=$work/home XDG_CACHE_HOME=$work/cache
# Every build here is this user's: the labs' through the build's ccache (lab_objects, tests/smoke/lib.sh), so that the
# new lab takes the precompiled header the example's build made.
[[ ${#lab_objects[@]} -eq 0 ]] || export "${lab_objects[@]}"
mkdir -p "$HOME" "$XDG_CACHE_HOME"
chmod 0711 "$HOME" "$XDG_CACHE_HOME"

cp -a "$FIXTURES/install" prefix
check "the installation (cli/install-tree's, copied) holds simlab and its CMake package" \
  test -x prefix/bin/simlab -a -f prefix/lib/cmake/simlab/simlabConfig.cmake
simlab=$work/prefix/bin/simlab
mkdir labs
cp -r "$SOURCE_DIR/examples/pendulum" labs/pendulum

run_capture verify "$simlab" assignment verify labs/pendulum
sed 's/^/    /' verify.out
check "verify builds the lab against the installed simlab and every check holds" \
  bash -c "test $(status_of verify) -eq 0 && grep -q '^ok    build: pendulum' verify.out && grep -q '^verify: .* 0 fail' verify.out"
check "the reference earns every point, the starter none" \
  bash -c "grep -q '^ok    reference: 100/100' verify.out && grep -q '^ok    starter: 0/100' verify.out"
check "each corpus case gets its expected score" \
  test "$(grep -c '^ok    corpus .* as expected$' verify.out)" -eq "$(ls labs/pendulum/corpus/*.toml | wc -l)"
check "the students' copy holds no hidden test and the CPU limit has its margin" \
  bash -c "grep -q '^ok    hidden: ' verify.out && grep -q '^ok    time limit: ' verify.out"
check "the lab was built in the user's cache, not in its folder or the prefix" \
  bash -c "test -d cache/simlab && ! find labs prefix -name CMakeCache.txt | grep -q ."

mkdir -p class/ada class/bob
cp labs/pendulum/solution/Pendulum.cpp class/ada/
cp labs/pendulum/starter/Pendulum.cpp class/bob/
run_capture grade "$simlab" grade labs/pendulum class --out grades
check "a class of the reference and the starter is graded: 100 and 0" \
  bash -c "test $(status_of grade) -eq 0 && grep -q '^ada,100,100,graded' grades/gradebook.csv &&
    grep -q '^bob,0,100,graded' grades/gradebook.csv"

run_capture package "$simlab" package gradescope labs/pendulum -o autograder.zip
check "the installed simlab makes the lab's Gradescope package" test "$(status_of package)" -eq 0
unzip -Z1 autograder.zip >listed.txt 2>/dev/null
check "it carries the lab with its hidden tests, without its solution or corpus" \
  bash -c "grep -qx labs/pendulum/grading/hidden.cpp listed.txt && grep -qx labs/pendulum/starter/Pendulum.cpp listed.txt &&
    ! grep -q '^labs/pendulum/solution/' listed.txt && ! grep -q '^labs/pendulum/corpus/' listed.txt"
unzip -q -o autograder.zip setup.sh run_autograder
check "its setup builds what a lab builds against, then the lab, and closes simlab's places with the lab" \
  bash -c "grep -qx 'targets=simlab_kit .*' setup.sh && grep -qx 'lab=labs/pendulum .*' setup.sh &&
    grep -q 'assignment build \"\$source_dir/\$lab\"' setup.sh && grep -q 'lock-course\" \${lab:+' setup.sh"
check "and run_autograder grades with the lab's folder" grep -qx 'assignment=labs/pendulum .*' run_autograder
# Gradescope's side: setup.sh builds simlab and the lab from the archive (the objects it shares with the build
# under test from that build's ccache: tests/smoke/lib.sh), and run_autograder grades the reference in full.
root=$work/autograder
mkdir -p "$root/source" "$root/submission" "$root/results"
unzip -q autograder.zip -d "$root/source"
shared_objects "$work"
SIMLAB_SKIP_APT=1 SIMLAB_JOBS=2 SIMLAB_CMAKE_ARGS="$shared_objects" "$root/source/setup.sh" >setup.log 2>&1
check "setup.sh builds simlab and the lab" bash -c "test $? -eq 0 && test -x '$root/source/build/bin/simlab'" ||
  tail -20 setup.log
check "and closes the lab's hidden tests to others" \
  test $((8#$(stat -c %a "$root/source/labs/pendulum/grading/hidden.cpp") & 7)) -eq 0
cp labs/pendulum/solution/Pendulum.cpp "$root/submission/"
AUTOGRADER_ROOT=$root "$root/source/run_autograder" >autograde.out 2>autograde.err
check "run_autograder grades the reference: 100/100 on 10 tests" \
  "$VALIDATE" "$root/results/results.json" --score 100 --max 100 --tests 10 || tail -5 autograde.err

run_capture student "$simlab" package student labs/pendulum -o bundle
check "the student bundle carries the lab without its solution, hidden tests or corpus" \
  bash -c "test $(status_of student) -eq 0 && test -f bundle/labs/pendulum/starter/Pendulum.cpp &&
    test ! -e bundle/labs/pendulum/solution && test ! -e bundle/labs/pendulum/grading/hidden.cpp &&
    test ! -e bundle/labs/pendulum/corpus && test -f bundle/scripts/setup"
# Nor any line of them under another name: every file of the bundle looked through (the look cli/package-secrets
# gives the course's packages; the lab in labs/ is examples/pendulum's copy, whose secret lines it knows).
run_capture look python3 "$SOURCE_DIR/tests/tools/package_secrets.py" "$SOURCE_DIR" bundle
sed 's/^/    /' look.out
check "  nor any line of its hidden tests or solution, whatever the file" test "$(status_of look)" -eq 0

# A new lab from the template, as docs/authors.md starts one: it verifies as written, and a bare name that is no
# course lab's is its folder.
run_capture new "$simlab" assignment new spring_lab
check "assignment new writes the template's lab under the new name" \
  bash -c "test $(status_of new) -eq 0 && test -f spring_lab/starter/SpringLab.cpp && test -f spring_lab/contract/SpringLab.h &&
    ! grep -rq -e mylab -e MyLab spring_lab"
run_capture newverify "$simlab" assignment verify spring_lab
sed 's/^/    /' newverify.out
check "and the new lab verifies" bash -c "test $(status_of newverify) -eq 0 && grep -q '^verify: .* 0 fail' newverify.out"
run_capture bare "$simlab" check spring_lab spring_lab/solution/SpringLab.cpp
check "simlab check spring_lab grades with the folder of that name" grep -q '^Score: 80/80' bare.out
run_capture badname "$simlab" assignment new 'Bad-Name'
check "a name that is no identifier is one line" \
  bash -c "test $(status_of badname) -eq 2 && test \$(wc -l <badname.err) -eq 1 && test ! -e Bad-Name"

# A wrong expectation: verify names it in one line and exits 1.
sed -i 's/^score = 35$/score = 40/' labs/pendulum/corpus/half-length.toml
run_capture broken "$simlab" assignment verify labs/pendulum
check "a corpus case that gets another score fails verify, in one line naming it" \
  bash -c "test $(status_of broken) -eq 1 && grep -q '^FAIL  corpus half-length: 35/100: score 35, expected 40' broken.out"
run_capture missing "$simlab" check labs/nowhere labs/pendulum/solution/Pendulum.cpp
check "a folder that is not there is one line" \
  bash -c "test $(status_of missing) -eq 2 && test \$(wc -l <missing.err) -eq 1 && grep -q 'no lab folder' missing.err"
finish
