# The study runs what the lab runs: rows of the apple's, the projectile's and the book's quick studies (the runs
# their handouts make, kept in $FIXTURES/handouts/<lab>), replayed through the lab programs as the study's table
# says: at the row's setting with one sample, at the end (--dt equal to the final time; at a fixed step
# --fixed-step --dt STEP, and --accuracy where the row names one). Each replay takes the row's steps, to the step,
# and prints the row's final digits within 0.05 (the program prints a tenth, trade.csv a hundredth: 0.055 between
# the two printings). Past 12 digits both need only be past 12: the rest is rounding, which the two need not share
# (Simbody times the ground hit to about 1e-14 s). CPodes takes the same steps but the last: in the lab program it
# steps past the final sample and interpolates it, where the study's run stops there (its stop time), so its rows
# agree to 0.15. A row whose energy moved a million times its scale (0 digits, a drift past 1e5 in trade.csv) is one
# the lab program stops as broken, saying so. The rows: each sweep's loosest ok setting and its dearest one up to
# 20000 evaluations, for the methods of every kind (Runge-Kutta, Euler, Verlet, the multistep CPodes).
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"

# rows CSV SUBJECT: "integrator mode accuracy step final_digits steps drift" of the rows replayed.
rows() {
  awk -F, -v subject="$2" 'NR > 1 && $2 == subject && $7 == "ok" && $9 != "" && $15 + 0 <= 20000 &&
      $3 ~ /^(RungeKuttaMerson|RungeKutta3|ExplicitEuler|SemiExplicitEuler|Verlet|CPodes)$/ {
    key = $3 "/" $4
    row = $3 " " ($4 == "accuracy" ? "accuracy" : "fixed") " " $5 " " $6 " " $9 " " $13 " " $11
    if (!(key in first)) { first[key] = row; order[++n] = key }
    last[key] = row
  }
  END { for (i = 1; i <= n; i++) { print first[order[i]]; if (last[order[i]] != first[order[i]]) print last[order[i]] } }' "$1"
}

# replay LABEL CSV SUBJECT FINAL_TIME FIGURE PROGRAM [SCENE_ARGS...]: the rows through PROGRAM. FIGURE is a pattern of
# the output lines whose digits the row's figure is (the worst of them).
replayed=0
replay() {
  local label=$1 csv=$2 subject=$3 final=$4 figure=$5 program=$6
  shift 6
  local integrator mode accuracy step digits steps drift args got gotSteps tolerance
  while read -r integrator mode accuracy step digits steps drift; do
    args=(--integrator "$integrator" --final-time "$final")
    if [[ $mode == accuracy ]]; then
      args+=(--accuracy "$accuracy" --dt "$final")
    else
      args+=(--fixed-step --dt "$step")
      if awk "BEGIN { exit !($accuracy > 0) }"; then args+=(--accuracy "$accuracy"); fi
    fi
    "$program" "$@" "${args[@]}" --quiet --output replay.txt >replay.out 2>replay.err
    got=$(grep -E "$figure" replay.out | sed -n 's/.*: \([0-9.]*\) accurate digits.*/\1/p' | sort -g | head -n 1)
    gotSteps=$(sed -n 's/.*, \([0-9]*\) steps[:)].*/\1/p' replay.out | tail -n 1)
    replayed=$((replayed + 1))
    if grep -q 'error: the run broke at' replay.err; then
      check "$label, $integrator $mode ${accuracy}/${step} s: the study's run drifts $drift times its energy; the program stops it as broken" \
        awk "BEGIN { exit !($digits < 0.5 && $drift > 1e5) }"
      continue
    fi
    tolerance=0.055
    [[ $integrator == CPodes ]] && tolerance=0.15
    check "$label, $integrator $mode ${accuracy}/${step} s: the study's $steps steps and $digits digits; the program's $gotSteps and $got" \
      awk -v a="$got" -v b="$digits" -v s="$gotSteps" -v t="$steps" -v e="$tolerance" \
      'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && s == t && (d <= e || (a >= 12 && b >= 12))) }'
  done < <(rows "$csv" "$subject")
}

apple=$FIXTURES/handouts/apple/solution-tree/study/trade.csv
projectile=$FIXTURES/handouts/projectile/solution-tree/study/trade.csv
book=$FIXTURES/handouts/book/solution-tree/study/trade.csv
for csv in "$apple" "$projectile" "$book"; do check "the handout's quick study wrote $csv" test -s "$csv"; done

replay apple "$apple" apple 4 'accurate digits' "$BIN_DIR/apple-reference"
# The projectile's final figure is its ground hit: the worse of t*'s and x*'s digits.
replay projectile "$projectile" projectile 6 '^  exact [tx]\*' "$BIN_DIR/projectile-reference"
for spin in min intermediate max; do
  replay "book, $spin axis" "$book" "book-$spin" 4 '^  exact ' "$BIN_DIR/book-reference" --spin "$spin"
done
check "rows of every lab were replayed ($replayed)" test "$replayed" -ge 40
finish
