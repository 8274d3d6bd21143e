# What the lab programs draw for people, headless: --plot writes a PNG or an SVG of the run against the exact
# solution, titled with its settings, and refuses other files in one line; simlab plot draws a results file later; --replay writes a page that Chromium
# opens without a console message and that shows the book turn; --animate, under Xvfb, shows each lab's body, and
# shows it moving (two screenshots of the visualizer's window, which differ where the body is).
# shellcheck source=lib.sh
source "$(dirname "$0")/lib.sh"
bin=$BIN_DIR

png_magic=$(printf '\211PNG')
is_png() { test "$(head -c 4 "$1")" = "$png_magic"; }
differing() { compare -metric AE "$1" "$2" null: 2>&1 | sed 's/ .*//'; }

run_capture apple "$bin/apple-reference" --quiet --output apple.txt --plot apple.png
check "apple --plot a.png draws a PNG" bash -c "test $(status_of apple) -eq 0 && grep -q 'Plot drawn in apple.png' apple.out"
check "  and it is one" is_png apple.png
run_capture projectile "$bin/projectile-reference" --quiet --output projectile.txt --plot projectile.svg
check "projectile --plot p.svg draws an SVG" test "$(status_of projectile)" -eq 0
check "  with the parabola, the ground hit and the settings in it" \
  bash -c "grep -q '<svg' projectile.svg && grep -q 'exact parabola' projectile.svg && grep -q 'ground hit: t = 5.23242 s' projectile.svg && grep -q 'RungeKuttaMerson, accuracy 1e-07' projectile.svg"
run_capture book "$bin/book-reference" --quiet --spin intermediate --output book.txt --plot book.png
check "book --spin intermediate --plot b.png draws a PNG" bash -c "test $(status_of book) -eq 0 && head -c 4 book.png | grep -q PNG"
run_capture svgbook "$bin/book-reference" --quiet --spin intermediate --output book.txt --plot book.svg
check "  titled with the spin and the integrator" \
  bash -c "grep -q 'about the intermediate axis' book.svg && grep -q 'simulated wx' book.svg && grep -q 'K / K(0) - 1' book.svg"
run_capture jpeg "$bin/apple-reference" --quiet --output apple.txt --plot apple.jpg
check "a plot that is not .png or .svg is a usage error, in one line" \
  bash -c "test $(status_of jpeg) -eq 2 && test \$(wc -l <jpeg.err) -eq 1 && grep -q 'a plot is a .png or an .svg file' jpeg.err"
run_capture nognuplot env PATH=/nonexistent "$bin/apple-reference" --quiet --output apple.txt --plot lost.png
check "without gnuplot the run says so in one line, and leaves no file" \
  bash -c "test $(status_of nognuplot) -eq 1 && test \$(wc -l <nognuplot.err) -eq 1 && grep -q 'needs gnuplot' nognuplot.err && ! test -e lost.png"

run_capture boot "$bin/babyboot" --quiet --output boot.txt --plot boot.svg
check "babyboot --plot draws a project's columns, one panel per unit" \
  bash -c "test $(status_of boot) -eq 0 && grep -q 'qA (the rod' boot.svg && grep -q 'uB (the rate of qB)' boot.svg && grep -q 'RungeKuttaMerson, accuracy 1e-07' boot.svg"

# simlab plot: a results file drawn afterwards by the lab program (here the starter's, which draws without running
# any student code), checked against the scene it names.
run_capture max "$bin/book-reference" --quiet --spin max --output max.txt
run_capture replot "$SIMLAB" plot book max.txt -o max.svg -- --spin max
check "simlab plot book max.txt -- --spin max draws the earlier run" \
  bash -c "test $(status_of replot) -eq 0 && grep -q 'about the max axis' max.svg && grep -q 'from max.txt' max.svg"
run_capture wrongscene "$SIMLAB" plot book max.txt -o wrong.svg
check "  and refuses, in one line, a file from another scene than the one given" \
  bash -c "test $(status_of wrongscene) -eq 1 && test \$(wc -l <wrongscene.err) -eq 1 && grep -q 'give the options of the run that wrote it' wrongscene.err && ! test -e wrong.svg"
run_capture notresults "$SIMLAB" plot apple max.txt
check "  or another program's file" bash -c "test $(status_of notresults) -eq 1 && grep -q 'is not a results file of this program' notresults.err"

# --replay: one page, opened from disk in headless Chromium, with nothing on its console; at two times the book
# stands differently.
if command -v chromium >/dev/null && test -f /usr/share/javascript/three/three.min.js; then
  run_capture replay "$bin/book-reference" --quiet --spin intermediate --output book.txt --replay book.html
  check "book --spin intermediate --replay b.html writes the page" \
    bash -c "test $(status_of replay) -eq 0 && grep -q 'Replay written to book.html' replay.out && test -s book.html"
  check "  which needs nothing but itself ($(wc -c <book.html) bytes)" \
    bash -c "! grep -Eq '<(script|link|img)[^>]* (src|href)=\"(https?:|//)' book.html"
  check "  opens in Chromium with nothing on the console" \
    "$SOURCE_DIR/tests/pages/page-check" book.html --shot t=0.5 replay-1.png --shot t=2.5 replay-2.png
  # The 3-D view is the page's left part under its header.
  convert replay-1.png -crop 700x600+0+120 +repage view-1.png && convert replay-2.png -crop 700x600+0+120 +repage view-2.png
  faces1=$(convert view-1.png -colorspace HSL -channel G -separate +channel -threshold 50% -format '%[fx:round(mean*w*h)]' info:)
  check "  showing the book's coloured faces ($faces1 coloured pixels)" awk "BEGIN { exit !($faces1 > 3000) }"
  check "  turned otherwise at t = 2.5 s than at 0.5 s ($(differing view-1.png view-2.png) pixels change)" \
    awk "BEGIN { exit !($(differing view-1.png view-2.png) > 3000) }"
  # The projectile's x slider carries a massless frame: no matter, so the page draws only the ball.
  run_capture projreplay "$bin/projectile-reference" --quiet --output projectile.txt --replay projectile.html
  check "projectile --replay marks its one massless body (the x slider's frame), which the page does not draw" \
    bash -c "test $(status_of projreplay) -eq 0 && test \$(grep -o '\"massless\":true' projectile.html | wc -l) -eq 1 && grep -q 'b.shapes === 0 && !b.massless' projectile.html"
  check "  and opens in Chromium with nothing on the console" "$SOURCE_DIR/tests/pages/page-check" projectile.html
else
  echo "skipped: --replay needs chromium and libjs-three (scripts/install-deps installs both)"
fi

# --animate: the visualizer in a virtual display; screenshots of the whole screen once the window shows something.
if ! command -v xvfb-run >/dev/null || ! command -v import >/dev/null; then
  echo "skipped: --animate needs xvfb-run and ImageMagick (scripts/install-deps installs both)"
  finish
fi
# Pixels of one colour (within 12 %) in an image; the strongly coloured pixels of one. Kept in a file: shoot.sh, run
# by xvfb-run's sh, reads them too.
cat > colours.sh <<'COLOURS'
pixels_of() {
  convert "$1" -fuzz 2% -fill black -opaque white -fuzz 12% -fill white -opaque "$2" -fuzz 0 -fill black +opaque white \
    -format '%[fx:round(mean*w*h)]' info:
}
coloured() { convert "$1" -colorspace HSL -channel G -separate +channel -threshold 50% -format '%[fx:round(mean*w*h)]' info:; }
COLOURS
# shellcheck source=/dev/null
source colours.sh
cat > shoot.sh <<'SHOOT'
#!/usr/bin/env bash
# shoot.sh NAME GAP DRAWN PROGRAM ARGS...: runs PROGRAM with --animate and takes two screenshots GAP s apart, the first
# once the visualizer has drawn its scene: the screen (black until the window shows) holds more than four colours and
# DRAWN, a shell condition on the screenshot ($shot), holds. A busy machine draws the first frames late; the scene is
# waited for while the program runs (150 tries, some 45 s), not for a fixed time.
name=$1 gap=$2 drawn=$3; shift 3
# shellcheck source=/dev/null
source ./colours.sh
"$@" --animate --quiet --output "$name.txt" >"$name.anim.out" 2>"$name.anim.err" &
program=$!
shot=$name-1.png
for _ in $(seq 1 150); do
  import -window root "$shot" 2>/dev/null
  [[ $(convert "$shot" -format %k info: 2>/dev/null || echo 0) -gt 4 ]] && eval "$drawn" && break
  kill -0 $program 2>/dev/null || break
  sleep 0.2
done
sleep "$gap"
import -window root "$name-2.png"
wait $program
SHOOT
chmod +x shoot.sh
shoot() { xvfb-run -a -s "-screen 0 1024x768x24" ./shoot.sh "$@" >/dev/null 2>&1; }

label='test "$(pixels_of "$shot" "#800000")" -gt 50'
shoot apple 1.5 "$label" "$bin/apple-reference" --final-time 6
check "apple --animate: the apple's label is on screen ($(pixels_of apple-1.png '#800000') pixels)" \
  awk "BEGIN { exit !($(pixels_of apple-1.png '#800000') > 50) }"
check "  and it falls ($(differing apple-1.png apple-2.png) pixels change)" awk "BEGIN { exit !($(differing apple-1.png apple-2.png) > 200) }"
# The projectile's scene is drawn once its ground (brown) fills the lower part of the window.
shoot projectile 1.5 'test "$(pixels_of "$shot" "#836237")" -gt 100000' "$bin/projectile-reference"
check "projectile --animate: the ball's trail and label are on screen, and move ($(differing projectile-1.png projectile-2.png) pixels change)" \
  awk "BEGIN { exit !($(differing projectile-1.png projectile-2.png) > 200) }"
# The book's background is white and its axes grey: the strongly coloured pixels are its faces.
shoot book 1.5 'test "$(coloured "$shot")" -gt 3000' "$bin/book-reference" --spin intermediate --final-time 10
faces1=$(coloured book-1.png) faces2=$(coloured book-2.png)
check "book --animate: the book is on screen, its faces coloured ($faces1 and $faces2 coloured pixels)" \
  awk "BEGIN { exit !($faces1 > 3000 && $faces2 > 3000) }"
check "  and it turns ($(differing book-1.png book-2.png) pixels change)" awk "BEGIN { exit !($(differing book-1.png book-2.png) > 2000) }"
finish
