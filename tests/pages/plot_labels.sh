# Every kind of figure simlab draws with gnuplot keeps its texts inside it as a browser draws them (svg-text-check
# measures each text's box in headless Chromium): each lab program's --plot, a project's three panels with an
# energy that hardly moves (its axis then reads "J, less" a reference value, beside wide tick labels), the trade
# study's plots and the long-run views, of the reference solution and of a student's file. The energy panel's
# ticks show the values' spread, not the rounding of the value they are less.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

command -v gnuplot >/dev/null || { echo "skipped: gnuplot is not installed"; exit 77; }
command -v chromium >/dev/null || command -v chromium-browser >/dev/null || { echo "skipped: no chromium"; exit 77; }
"$BIN_DIR/apple-reference" --quiet --plot apple.svg >/dev/null
"$BIN_DIR/projectile-reference" --quiet --plot projectile.svg >/dev/null
"$BIN_DIR/book-reference" --quiet --spin intermediate --plot book.svg >/dev/null
"$BIN_DIR/babyboot" --quiet --plot boot.svg >/dev/null
# Hanging and swinging half a radian a second: an energy of -0.203 J that keeps 12 digits.
"$BIN_DIR/babyboot" --quiet --set qA=0 --set uA=0.5 --plot offset.svg >/dev/null
"$SIMLAB" study trade apple --question --quick -o trade --file "$SOURCE_DIR/solutions/apple/NewtonsApple.cpp" >/dev/null 2>&1
"$SIMLAB" study long-run biosim --quick -o view >/dev/null 2>&1
"$SIMLAB" study long-run book --quick -o own --file "$SOURCE_DIR/solutions/book/BookSpin.cpp" >/dev/null 2>&1
figures=(apple.svg projectile.svg book.svg boot.svg offset.svg trade/apple-question-evaluations.svg
         trade/apple-question-time.svg view/biosim-long-run.svg own/book-long-run.svg)
for figure in "${figures[@]}"; do
  check "$figure is drawn" test -s "$figure"
done
# And the check sees a label cut: an axis label 6 px past a figure's left edge, as gnuplot's margin once left one.
cat >cut.svg <<'SVG'
<?xml version="1.0" encoding="utf-8"?>
<svg width="200" height="100" viewBox="0 0 200 100" xmlns="http://www.w3.org/2000/svg">
<g transform="translate(2,50) rotate(270)"><text font-family="sans" font-size="11" text-anchor="middle">J, less -9.810000097</text></g>
<text x="100" y="50" font-family="sans" font-size="11" text-anchor="middle">inside</text>
</svg>
SVG
run_capture cut "$SOURCE_DIR/tests/pages/svg-text-check" cut.svg apple.svg
check "svg-text-check names a label cut at a figure's edge, and that figure alone" \
  bash -c "test $(status_of cut) -eq 1 && grep -q \"cut.svg: a text reaches past the figure's edge: 'J, less -9.810000097' at -\" cut.err &&
           ! grep -q apple.svg cut.err"
run_capture extents "$SOURCE_DIR/tests/pages/svg-text-check" "${figures[@]}"
check "every text of the ${#figures[@]} figures lies inside it, as Chromium draws it" test "$(status_of extents)" -eq 0 ||
  cat extents.err
check "the energy that hardly moves is drawn less a reference value written to the digits its spread needs" \
  grep -qE 'J, less -0\.2030186013[0-9]{4,}' offset.svg
# Its ticks differ: they read the spread (about 1e-13 J), not a rounding of the reference value shared by all.
check "  so that its tick labels differ from one another" \
  test "$(grep -oE '>-?[0-9]\.[0-9]e-1[0-9]<' offset.svg | sort -u | wc -l)" -ge 4
finish
