# simlab similarity: pairs far more alike than the class, once the starter's lines are removed. A class of five:
# the reference, the reference with its names changed and its comments gone, the reference with one edit (a corpus
# case), and two students who handed in the starter unchanged, whose files share only the starter's lines. The
# three copies are listed, each pair side by side; the two starters are not; the page escapes an id that is markup.
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
  bash -c "grep -qE '%  ada  bob$' similarity.out && grep -qE '%  <b>eve&  ada$' similarity.out &&
           grep -qE '%  <b>eve&  bob$' similarity.out && test \$(grep -c ' %  ' similarity.out) -eq 3"
check "two unchanged starters are not: the starter's lines are removed first" \
  bash -c "! grep -qE '  (cy  dan|dan  cy)$' similarity.out"
check "the page shows each pair side by side, escaped, with nothing that runs" \
  bash -c "test \$(grep -c 'class=\"pair\"' out/similarity.html) -eq 3 && grep -q '&lt;b&gt;eve&amp;' out/similarity.html &&
           ! grep -q '<b>eve' out/similarity.html && ! grep -qi '<script' out/similarity.html"
finish
