# simlab similarity: pairs far more alike than is likely by chance, once the starter's code is removed.
# A class of five: the reference, the reference with its names changed and its comments gone, the reference with
# one edit (a corpus case), and two students who handed in the starter unchanged, whose files share only the
# starter's code. The three copies are flagged, each pair side by side; the two starters are not; the page escapes
# an id that is markup.
# Then a scaffolded class, where every honest solution looks alike: five honest students, each the reference with
# a few edits of their own, one identical copy and one renamed copy. Both copies share all their own code with
# their originals once the starter's code is removed by its tokens (renamed as it is): the class-relative threshold
# and the floor flag both, and no honest pair; the page marks the shared lines, escaped.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

reference=$SOURCE_DIR/solutions/apple/NewtonsApple.cpp
hostile='<b>eve&'
mkdir -p class/ada class/bob class/cy class/dan "class/$hostile"
cp "$reference" class/ada/NewtonsApple.cpp
sed 's/\bp_GA\b/position/g; s/\bsystem\b/world/g; s|//.*$||' "$reference" >class/bob/NewtonsApple.cpp
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" class/cy/
cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" class/dan/
"$CORPUS" materialize apple "$SOURCE_DIR/tests/corpus/apple/euler-coarse-step.toml" --out cases >/dev/null
cp cases/euler-coarse-step/NewtonsApple.cpp "class/$hostile/"

run_capture similarity "$SIMLAB" similarity apple class -o out
check "similarity succeeds and writes its page" bash -c "test $(status_of similarity) -eq 0 && test -s out/similarity.html"
check "the three copies are listed, pair by pair" \
  bash -c "grep -qE '%  floor, class  ada  bob  \(' similarity.out &&
           grep -qE '%  floor, class  <b>eve&  ada  \(' similarity.out &&
           grep -qE '%  floor, class  <b>eve&  bob  \(' similarity.out && test \$(grep -c ' %  ' similarity.out) -eq 3"
check "two unchanged starters are not: the starter's code is removed first" \
  bash -c "! grep -qE '  (cy  dan|dan  cy)$' similarity.out"
check "the page shows each pair side by side, escaped, with nothing that runs" \
  bash -c "test \$(grep -c 'class=\"pair\"' out/similarity.html) -eq 3 && grep -q '&lt;b&gt;eve&amp;' out/similarity.html &&
           ! grep -q '<b>eve' out/similarity.html && ! grep -qi '<script' out/similarity.html"

# The scaffolded class: each honest student edits two or three of the five places the starter leaves to write.
# shellcheck source=similarity_class.sh
source "$SOURCE_DIR/tests/cli/similarity_class.sh"
scaffold_class scaffold "$reference"
# The copy of ann's holds a hostile comment in its shared lines: markup, a control character, invalid UTF-8
# (shown as \x01 and U+FFFD).
mkdir -p scaffold/copy scaffold/renamed
perl -pe 's|^(\s*return state;)$|$1\n    // </pre><script>alert(1)</script>\x01\xff|' scaffold/ann/NewtonsApple.cpp \
  >scaffold/copy/NewtonsApple.cpp
perl -pe 's/\bstate\b/s/g; s/\bintegrator\b/integ/g; s/\bappleBody\b/body/g; s/\bchoice\b/settings/g; s/\bmodel\b/m/g' \
  scaffold/ben/NewtonsApple.cpp >scaffold/renamed/NewtonsApple.cpp

run_capture class "$SIMLAB" similarity apple scaffold -o scaffold-out --floor 100
check "the class-relative threshold alone flags both copies: the renamed starter is the starter, by its tokens" \
  bash -c "test $(status_of class) -eq 0 && grep -qE '%  (floor, )?class +ann  copy  \(' class.out &&
           grep -qE '%  (floor, )?class +ben  renamed  \(' class.out && test \$(grep -c ' %  ' class.out) -eq 2"
run_capture scaffold "$SIMLAB" similarity apple scaffold -o scaffold-out
check "the floor flags the identical and the renamed copy, and says so" \
  bash -c "test $(status_of scaffold) -eq 0 && grep -qE ' (9[0-9]|100) %  floor(, class)? +ann  copy  \(similarity.html#pair[01]\)$' scaffold.out &&
           grep -qE ' (9[0-9]|100) %  floor(, class)? +ben  renamed  \(similarity.html#pair[01]\)$' scaffold.out"
check "no honest pair is flagged: each shares under 90 %" bash -c "test \$(grep -c ' %  ' scaffold.out) -eq 2"
page=scaffold-out/similarity.html
section() { sed -n "/<section id=\"pair$1\">/,/<\/section>/p" "$page"; }
copy_pair=$(grep -oE 'pair[01]\)$' scaffold.out | head -1 | tr -d ')')  # the first flagged line is ann and copy
copy_pair=${copy_pair#pair}
check "the flagged pairs are listed on the page, each with its rule and a link to its side by side" \
  bash -c "grep -qE 'href=\"#pair$copy_pair\">ann</a></td><td class=\"name\">copy</td><td class=\"num\">[0-9]+ %</td><td>floor' $page &&
           grep -qE '>ben</a></td><td class=\"name\">renamed</td><td class=\"num\">[0-9]+ %</td><td>floor' $page"
section "$copy_pair" >copy-pair.html
check "the copy's side by side marks the shared lines in both columns" \
  bash -c "grep -qE 'Shared runs: 1\. lines [0-9]+-[0-9]+ of ann and [0-9]+-[0-9]+ of copy' copy-pair.html &&
           test \$(grep -c '<mark class=\"r0\" title=\"shared run 1\">    integrator-&gt;setAccuracy(run.accuracy);</mark>' copy-pair.html) -eq 2 &&
           grep -q '<span class=\"muted\">}</span>' copy-pair.html"
check "the hostile line is shown escaped, marked, and nothing of it runs" \
  bash -c "grep -qF '>    // &lt;/pre&gt;&lt;script&gt;alert(1)&lt;/script&gt;\\x01�</mark>' copy-pair.html &&
           ! grep -qi '<script' $page && ! LC_ALL=C grep -qP '[\x01\xff]' $page"
run_capture floor "$SIMLAB" similarity apple scaffold -o scaffold-out --floor 150
check "a floor outside 1 to 100 is refused" bash -c "test $(status_of floor) -ne 0 && grep -q 'floor' floor.err"
finish
