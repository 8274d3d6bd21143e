# The replay page's style sheet and script are files of their own (assignments/support/assets), inlined in every
# page: neither may hold what would end its inline element early, nor the marker that ends the raw string the
# build makes of it. (That the script runs without a console line is tests/pages/replay-check's, in Chromium.)
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

assets=$SOURCE_DIR/assignments/support/assets
check "the script holds no </script (it would end the page's <script> element)" \
  bash -c "! grep -qi '</script' '$assets/replay.js'"
check "the style sheet holds no </style" bash -c "! grep -qi '</style' '$assets/replay.css'"
check "neither holds the end marker of the raw string it is built into" \
  bash -c "! grep -qF ')simlab-text\"' '$assets/replay.js' '$assets/replay.css'"
check "the script is strict JavaScript in one function, as the page expects" \
  bash -c "head -n 2 '$assets/replay.js' | grep -q '\"use strict\"' && tail -n 1 '$assets/replay.js' | grep -q '^})();'"
finish
