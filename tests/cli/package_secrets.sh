# Packages students can reach hold no secret: every file of the student bundle, the GitHub Classroom template and a
# PrairieLearn question's pullable image and pages is looked through for any line of a hidden test or a solution
# (tests/tools/package_secrets.py). The question's tests/ folder, which PrairieLearn keeps from students, is where
# the hidden tests go: the same look finds them there.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
look() { python3 "$SOURCE_DIR/tests/tools/package_secrets.py" "$SOURCE_DIR" "$@"; }

for lab in apple projectile book biosim; do
  run_capture "question-$lab" "$SIMLAB" package prairielearn "$lab" -o "question-$lab"
  check "package prairielearn $lab succeeds" test "$(status_of "question-$lab")" -eq 0
done
run_capture classroom "$SIMLAB" package github-classroom apple -o classroom
check "package github-classroom succeeds" test "$(status_of classroom)" -eq 0
run_capture bundle "$SIMLAB" package student -o bundle
check "package student succeeds" test "$(status_of bundle)" -eq 0
# (A bundle with a lab of one's own, whose solution and hidden tests are as secret as the course's, is looked
# through by cli/authoring, which has built the example lab.)

pulled=(bundle classroom)
for lab in apple projectile book biosim; do
  pulled+=("question-$lab/image")
  mkdir -p "question-$lab-pages" && cp question-"$lab"/*.* "question-$lab-pages/"
  pulled+=("question-$lab-pages")
done
run_capture look look "${pulled[@]}"
sed 's/^/    /' look.out
check "no line of a hidden test or a solution in what students can reach" test "$(status_of look)" -eq 0
# simlab list --secrets and the bundle agree: nothing it lists is in the bundle, and nothing in the bundle lies under
# anything it lists (the worked example's solution, which students are given, is no secret).
run_capture secrets "$SIMLAB" list --secrets
(cd bundle && find . -type f | sed 's|^\./||' | sort) >bundled.txt
disagree=0
while IFS= read -r secret; do
  rel=${secret#"$SOURCE_DIR"/}
  [[ $rel == "$secret" ]] && continue  # the build's and caches' paths are not the sources'
  if grep -qE "^$(printf '%s' "$rel" | sed 's/[.[\*^$]/\\&/g')(/|$)" bundled.txt; then
    echo "    listed as secret, and bundled: $rel"
    disagree=$((disagree + 1))
  fi
done <secrets.out
check "simlab list --secrets and the student bundle agree ($(wc -l <secrets.out) secrets listed)" \
  bash -c "test $(status_of secrets) -eq 0 && test $disagree -eq 0 && ! grep -q '/solutions/biosim' secrets.out"
run_capture tests look question-apple/tests question-book/tests
check "the questions' tests/ folders hold the hidden tests (the look finds them there)" \
  bash -c "test $(status_of tests) -eq 1 && grep -q 'hidden.cpp' tests.out"
finish
