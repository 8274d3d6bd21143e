# simlab package student: the bundle holds no solution, hidden test or expected value, builds from scratch with
# its own scripts/setup, and self-checks: the starter low, a finished file full marks on the visible tests. The
# built bundle is kept in $FIXTURES/bundle: a PrairieLearn question's image is the same sources
# (cli/package-prairielearn builds its judge there).
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

rm -rf "$FIXTURES/bundle" && mkdir -p "$FIXTURES"
ln -s "$FIXTURES/bundle" bundle
run_capture package "$SIMLAB" package student -o "$FIXTURES/bundle"
check "package student succeeds" test "$(status_of package)" -eq 0
check "the bundle has no solutions/ but the worked example project's" \
  bash -c "test \"\$(ls bundle/solutions)\" = biosim -a -f bundle/solutions/biosim/Project.cpp"
check "the bundle has no hidden tests" test ! -e bundle/assignments/apple/grading/hidden.cpp
check "the bundle has no corpus or CI" test ! -e bundle/tests -a ! -e bundle/.ci
check "the bundle keeps the starter and the handout" test -f bundle/starter/apple/NewtonsApple.cpp -a -f bundle/handouts/apple.md
# Nothing of the solution's code or of the hidden variants' values is anywhere in it.
check "no line of the solution's model" bash -c "! grep -rqF 'model.apple.setOneQ(state, 0, scene.dropHeight);' bundle"
# (The replay pages hold the reference runs' sampled values, among them a speed of -24.794 m/s: not a variant's.)
check "no hidden variant's values (Jupiter's gravity, the long fall)" \
  bash -c "! grep -rqE '\b24\.79|\b50000\b' --exclude-dir=third_party --exclude='*-replay.html' bundle"
if git -C "$SOURCE_DIR" rev-parse --git-dir >/dev/null 2>&1; then
  check "every file in it is one git tracks, or one the packaging made (no build log, no untracked file)" \
    python3 - "$SOURCE_DIR" bundle <<'PY'
import os, re, subprocess, sys
tracked = set(subprocess.run(["git", "-C", sys.argv[1], "ls-files"], capture_output=True, text=True).stdout.split("\n"))
made = re.compile(r"^(README\.md|third_party/catch2/.*|handouts/[a-z]+(-replay)?\.html|handouts/figures/[a-z]+-reference\.svg)$")
stray = [os.path.relpath(os.path.join(r, f), sys.argv[2]) for r, _, fs in os.walk(sys.argv[2]) for f in fs]
stray = [f for f in stray if f not in tracked and not made.match(f)]
assert not stray, stray
PY
fi
check "the student README replaces the instructors'" grep -q 'Fill in the .SIMLAB_TODO' bundle/README.md
check "it carries the licence, the third-party notices and Catch2's licence beside its header" \
  bash -c "grep -q 'Apache License' bundle/LICENSE && grep -q 'three.js' bundle/THIRD_PARTY_NOTICES.md && grep -q 'Boost Software License' bundle/third_party/catch2/LICENSE_1_0.txt"
check "each handout is a page too, with the reference run's plot and replay" \
  bash -c "for lab in apple projectile book biosim; do test -f bundle/handouts/\$lab.html -a -f bundle/handouts/\$lab-replay.html -a -f bundle/handouts/figures/\$lab-reference.svg || exit 1; done"
check "  which say so" grep -q 'made: 4 handout pages (handouts/<id>.html), 4 with the reference run' package.out
if command -v chromium >/dev/null; then
  for page in apple projectile book biosim; do
    check "  handouts/$page.html opens offline in Chromium, every link resolving, every block rendered as written" \
      "$SOURCE_DIR/tests/pages/page-check" "bundle/handouts/$page.html" --links --markdown "bundle/handouts/$page.md"
  done
  check "  and so does a replay" "$SOURCE_DIR/tests/pages/page-check" bundle/handouts/book-replay.html
fi
run_capture again "$SIMLAB" package student -o "$FIXTURES/bundle"
check "it refuses to write into a folder that is not empty" test "$(status_of again)" -eq 2

# Build it as a student would, with its own scripts/setup in a folder of its own (packages are already installed
# here), as on a system whose Catch2 is not 2.13 (Ubuntu 24.04): from the header the bundle carries. Every step is
# run; an object whose source and flags are the same as one the build under test compiled comes from that build's
# ccache (most of them: what differs, such as the carried Catch2 header, is compiled).
shared_objects "$FIXTURES/bundle"
SIMLAB_SKIP_APT=1 SIMLAB_JOBS=2 SIMLAB_CMAKE_ARGS="-DCMAKE_DISABLE_FIND_PACKAGE_Catch2=ON $shared_objects" \
  "$FIXTURES/bundle/scripts/setup" >build.log 2>&1
check "the bundle builds with its own scripts/setup and its Catch2 header" \
  bash -c "test $? -eq 0 && grep -q 'Catch2 2.13: the header in third_party/catch2' build.log" || tail -20 build.log
bundled=$FIXTURES/bundle/build/bin/simlab
# What a student's setup builds: simlab, each lab's program and grader; no study program until one is asked for.
check "  simlab, each lab's program and judge, and the worked example's program" bash -c \
  "for f in bin/simlab bin/apple bin/projectile bin/book bin/project bin/babyboot judges/apple-judge judges/biosim-judge; do
     test -x '$FIXTURES/bundle/build/'\$f || exit 1; done"
# (A course source the study shares with the program or the probe, <id>_course's, is built for them.)
check "  and no study program or object of the study's own" python3 - "$FIXTURES/bundle/build/simlab-build.json" <<'PY'
import json, os, sys
m = json.load(open(sys.argv[1]))
built, own = [], 0
for a in m["assignments"]:
    shared = set(a["program_objects"]) | set(a["probe_objects"])
    studys_own = [p for p in a["study_objects"] if p not in shared]
    own += len(studys_own)
    built += [p for p in studys_own + [a["study_program_path"]] if p and os.path.exists(p)]
assert not built, built
assert own, "no study object of a study's own to look for"
PY
run_capture starter "$bundled" check apple
check "the bundle's simlab checks its starter: 0/76" grep -q '^Score: 0/76$' starter.out
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" finished.cpp
run_capture finished "$bundled" check apple finished.cpp
check "a finished file scores 76/76 on the visible tests" grep -q '^Score: 76/76$' finished.out
check "and 5 hidden tests worth 24 points are left" grep -q '5 hidden tests worth 24 points are left' finished.out
# A student asks for a study of their file: the studies are built then, once; the trade question's table gives the
# digits it asks (3). The bundle's pages run their examples with these studies (bundle/..., after this test).
run_capture question "$bundled" study trade apple --question --quick --no-plots -o question --file finished.cpp
check "a student's first study builds the studies, once, then studies their file" \
  bash -c "test $(status_of question) -eq 0 && grep -q 'building the studies first, once' question.err &&
           grep -qE '^  3 +ExplicitEuler, fixed step' question.out"
run_capture nofile "$bundled" study trade apple --quick -o nofile
run_capture nofile_long "$bundled" study long-run book --quick -o nofile
check "a study with no file names the student's own, in one line: the bundle has no reference solution" \
  bash -c "test $(status_of nofile) -eq 2 -a $(status_of nofile_long) -eq 2 &&
           grep -q 'study your own file with --file (e.g. --file .*/starter/apple/NewtonsApple.cpp)' nofile.err &&
           grep -q 'follow your own file with --file (e.g. --file .*/starter/book/BookSpin.cpp)' nofile_long.err"
run_capture again_question "$bundled" study trade apple --question --quick --no-plots -o question --file finished.cpp
check "  and the next builds nothing" bash -c "test $(status_of again_question) -eq 0 && ! grep -q 'building the studies' again_question.err"
run_capture all "$bundled" check apple finished.cpp --all
check "--all is refused: the bundle has no hidden tests" grep -q 'does not have' all.err
run_capture grade "$bundled" grade apple
check "grading is refused in the bundle" test "$(status_of grade)" -eq 2
finish
