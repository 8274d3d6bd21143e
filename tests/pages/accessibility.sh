# Every kind of page simlab writes meets WCAG 2.1 AA as far as axe-core checks it (its rules tagged wcag2a, wcag2aa,
# wcag21a and wcag21aa), in the light colour scheme and the dark one where a page has it, in one headless Chromium
# (tests/pages/axe): the handout pages and each lab's replay from the student bundle, the project's replay among
# them; a replay written by a lab program (book.html); the class report; a student's feedback when every test
# passed, when one failed, when the file did not compile, crashed or ran out of time, with three plots of the run
# (the book) and with the model's drawings and items graded by hand (the project); and the similarity page. A
# replay is also worked from the keyboard alone. What no rule checks is checked here: each plot's text alternative
# says what it shows and gives its points as tables, and each outcome is said in words and a symbol, not by colour
# alone.
# Skipped (77) when Chromium is not installed, as the other page tests are; fails when Node.js or the npm packages
# (scripts/install-deps installs both) are missing.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

if ! command -v chromium >/dev/null && ! command -v chromium-browser >/dev/null; then
  echo "SKIP: chromium is not installed (scripts/install-deps installs it)"
  exit 77
fi
axe=$SOURCE_DIR/tests/pages/axe
if ! command -v node >/dev/null; then
  echo "FAIL: node is not installed: scripts/install-deps installs Node.js and the page checks' npm packages"
  exit 1
fi
if [[ ! -f $axe/node_modules/axe-core/axe.min.js || ! -f $axe/node_modules/puppeteer-core/package.json ]]; then
  echo "FAIL: the page checks' npm packages are not in $axe/node_modules: scripts/install-deps installs them (npm ci)"
  exit 1
fi

started=$SECONDS
# The handouts and the replays, as the student bundle has them; a lab program's replay of its own.
run_capture package "$SIMLAB" package student -o bundle
handout_pages=(bundle/handouts/*.html)
check "the student bundle is made, with its handout pages" test "${#handout_pages[@]}" -eq 8
run_capture replay "$BIN_DIR/book-reference" --quiet --spin intermediate --output book.txt --replay book.html
check "book-reference --replay writes book.html" test "$(status_of replay)" -eq 0

# The book's and the project's reference graded alone (their feedback draws plots, the model, manual items), side
# by side; the apple's sample class as cli/grade-sample-class graded it.
for lab in book biosim; do
  mkdir -p "class-$lab/reference" && cp "$SOURCE_DIR/solutions/$lab"/* "class-$lab/reference/"
  "$SIMLAB" grade "$lab" "class-$lab" --out "grades-$lab" --jobs 1 >"grade-$lab.out" 2>&1 &
done
wait
graded=$FIXTURES/apple-graded
for lab in book biosim; do
  check "the $lab's reference is graded" test -s "grades-$lab/students/reference/feedback.html"
done

# The similarity page: a copy, a renamed copy and the starter.
mkdir -p similar/ada similar/bob similar/cy
cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" similar/ada/
sed 's/\bp_GA\b/position/g; s|//.*$||' "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" >similar/bob/NewtonsApple.cpp
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" similar/cy/
run_capture similarity "$SIMLAB" similarity apple similar -o similarity
check "simlab similarity writes its page" test -s similarity/similarity.html

pages=("${handout_pages[@]}" book.html "$graded/report.html" grades-book/report.html grades-biosim/report.html
       grades-book/students/reference/feedback.html grades-biosim/students/reference/feedback.html
       similarity/similarity.html)
for student in reference wrong-height compile-error segfault infinite-loop; do
  pages+=("$graded/students/$student/feedback.html")
done
made=$SECONDS
node "$axe/axe-check.js" "${pages[@]}" >axe.out 2>&1
status=$?
cat axe.out
echo "the pages made in $((made - started)) s, checked in $((SECONDS - made)) s"
check "axe-core finds no WCAG 2.0/2.1 A or AA rule broken on any of the ${#pages[@]} pages" test "$status" -eq 0
check "  and checked every one" grep -q "^axe-check: ${#pages[@]} pages, 0 rules broken" axe.out
check "  with a replay worked from the keyboard alone" grep -q 'replay.html: keyboard: Tab reaches' axe.out

# Each plot's text alternative: its title as the image's alt, what it shows in words beside it, its points as tables.
check "the book's feedback shows its three plots, each with its alt, its description and its points" python3 - \
  grades-book/students/reference/feedback.html <<'PY'
import re, sys
page = open(sys.argv[1], encoding="utf-8").read()
figures = re.findall(r'<figure id="(picture-\d)"><img [^>]*alt="Plot: The spinning book: about the (\w+) axis[^"]*" '
                     r'aria-describedby="\1-about"[^>]*><figcaption><p id="\1-about">([^<]*)</p>', page)
assert len(figures) == 3, f"{len(figures)} plots described"
for name, axis, said in figures:
    assert f"about the {axis} axis" in said and "simulated wx, " in said and "on the line exact wx as drawn" in said, said
    tables = re.search(f'<details class="data" id="{name}-data">(.*?)</details>', page, re.S)
    assert tables and tables.group(1).count("<table>") == 3, f"{name}: no tables of its points"
    assert '<th scope="col">simulated wx</th>' in tables.group(1)
PY
check "the handout's reference run is described from its data (the parabola, the ground hit) with its points" \
  bash -c "grep -q 'aria-describedby=\"reference-plot-about\"' bundle/handouts/projectile.html &&
           grep -q 'exact parabola, a line, from 0 at 0' bundle/handouts/projectile.html &&
           grep -q '<caption>Marked on height y (m) against range x (m)</caption>' bundle/handouts/projectile.html"
check "a handout's own figure drawn by simlab (the long run) is shown with its description and its points" \
  bash -c "grep -q 'alt=\"Plot: book, the spin about the intermediate axis: energy digits are not trajectory digits' bundle/handouts/book.html &&
           grep -q 'id=\"figure-1-about\">book, the spin about the intermediate axis' bundle/handouts/book.html &&
           grep -q '<details class=\"data\" id=\"figure-1-data\">' bundle/handouts/book.html"
check "every code block of a handout takes the keyboard's focus, named" \
  bash -c "test \$(grep -o '<pre' bundle/handouts/book.html | wc -l) -eq \$(grep -o '<div class=\"code\" tabindex=\"0\" role=\"group\" aria-label=\"[a-zA-Z+ ]*, example [0-9]*\">' bundle/handouts/book.html | wc -l)"
check "the replay says the motion in words" grep -q '<p id="motion">From t = 0 s to t = 4 s, [0-9]* frames. Body 1 (a brick and frame): its origin stays at (0, 0, 0) m; it turns through' book.html
check "the report's histogram says its counts" \
  grep -qE 'role="img" aria-label="Students per tenth of the points: [0-9]+ to under [0-9]+, [0-9]+ students?' "$graded/report.html"
check "an outcome is a word after a symbol, not a colour alone" \
  bash -c "grep -q '<span class=\"badge pass\"><span aria-hidden=\"true\">✓</span> passed</span>' $graded/students/reference/feedback.html &&
           grep -q '<span class=\"badge fail\"><span aria-hidden=\"true\">✗</span> failed</span>' $graded/students/wrong-height/feedback.html &&
           grep -q '<span class=\"badge error\"><span aria-hidden=\"true\">⚠</span> ' $graded/students/compile-error/feedback.html"
finish
