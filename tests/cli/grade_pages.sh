# simlab grade writes report.html and each student's feedback.html: pages that open in headless Chromium from
# disk with nothing on the console, whose links all resolve, hostile ids included; a resumed batch writes them too.
# Skipped (77) when Chromium is not installed.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

page_check=$SOURCE_DIR/tests/pages/page-check
if ! command -v chromium >/dev/null && ! command -v chromium-browser >/dev/null; then
  echo "SKIP: chromium is not installed (scripts/install-deps installs it)"
  exit 77
fi

# A small class: three of the sample class and a student whose id is markup.
mkdir class
for id in reference segfault compile-error; do cp -r "$BIN_DIR/../sample-class/apple/$id" class/; done
hostile='<i>x & "y" it'"'"'s'
mkdir "class/$hostile" && cp "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" "class/$hostile/"

run_capture grade "$SIMLAB" grade apple class --out grades --jobs 2
cat grade.out
check "grade exits 0" test "$(status_of grade)" -eq 0
check "the final line names report.html and feedback.html" grep -q 'report.html and .*feedback.html' grade.out
check "report.html is written" test -s grades/report.html
check "every student has feedback.html beside feedback.md" \
  test "$(ls grades/students/*/feedback.html | wc -l)" -eq 4 -a "$(ls grades/students/*/feedback.md | wc -l)" -eq 4
check "the hostile id is escaped in the report" grep -q '&lt;i&gt;x &amp; &quot;y&quot; it&apos;s' grades/report.html
check "and linked by its URL-encoded folder" \
  grep -q 'href="students/%3Ci%3Ex%20%26%20%22y%22%20it%27s/feedback.html"' grades/report.html
check "report.html loads cleanly and every link resolves" "$page_check" grades/report.html --links
check "a student's feedback.html loads cleanly and its links resolve" \
  "$page_check" grades/students/segfault/feedback.html --links
check "the reference's feedback.html loads cleanly and its links resolve (your-run.svg beside it)" \
  "$page_check" grades/students/reference/feedback.html --links --shot runs reference-runs.png
check "and draws the run the tests plotted inside the page: an SVG with the simulated and the exact curves" \
  python3 - grades/students/reference/feedback.html <<'PY'
import base64, re, sys, xml.etree.ElementTree as ET
page = open(sys.argv[1], encoding="utf-8").read()
found = re.findall(r'<img src="data:image/svg\+xml;base64,([A-Za-z0-9+/=]+)"', page)
assert len(found) == 1, f"{len(found)} inline SVG pictures"
svg = ET.fromstring(base64.b64decode(found[0]))
text = " ".join(svg.itertext())
assert "simulated y" in text and "exact: h - g t^2/2" in text, text[:300]
assert len(svg.findall(".//{http://www.w3.org/2000/svg}path")) > 10
PY
check "a file that did not compile drew no run, and its page says nothing of one" \
  bash -c "! grep -q 'Your runs, drawn' grades/students/compile-error/feedback.html"
check "the hostile student's feedback.html loads cleanly" "$page_check" "grades/students/$hostile/feedback.html"
check "a compile error's feedback.html loads cleanly" "$page_check" grades/students/compile-error/feedback.html

# Resumed: nothing is regraded, and what is missing is written again.
rm grades/report.html grades/students/reference/feedback.html
run_capture again "$SIMLAB" grade apple class --out grades --jobs 2
check "the rerun succeeds" test "$(status_of again)" -eq 0
check "it regrades nobody" test "$(grep -c '(unchanged)' again.out)" -eq 4
check "it writes report.html again" "$page_check" grades/report.html --links
check "and the feedback.html that was missing" test -s grades/students/reference/feedback.html
check "no temporary file is left behind" test -z "$(find grades -name '*.tmp.*')"
finish
