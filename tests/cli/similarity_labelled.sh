# simlab similarity on a labelled class: which pairs are copies is known, and the run is scored by its precision
# (of the pairs flagged, the copies) and its recall (of the copies, those flagged). docs/instructors.md gives the
# figures; SIMLAB=another simlab measures that one on the same class.
# The class: five honest students of a scaffolded lab (each the reference with edits of their own), two who wrote
# their own code in the starter's places, two who handed in the starter unchanged, and seven copies, each of one honest student, made as copiers make them:
#   copy      ann's, its comments changed
#   renamed   ben's, every name the student chose and every name of the starter's renamed
#   reordered cat's, its functions in another order and its names renamed
#   kept      dan's, its comments gone and its own names renamed, the starter's code as given
#   starter   eli's, the starter's names renamed (its parameters, the stepper), the student's own kept
#   sly       pia's (who wrote two of the five places, in code of her own), its comments gone and every name renamed
#   quip      quin's (who wrote each place in a few lines of her own), its comments gone and every name renamed
#   spelt     the copy of ann's, its comments gone, spelt with digraphs, alternative tokens and lines split
#             inside names (a copy of two files: ann's and the copy)
# Every copy is flagged and no honest pair is: precision and recall 1.
# shellcheck source=../smoke/lib.sh
source "$(dirname "$0")/../smoke/lib.sh"
# shellcheck source=similarity_class.sh
source "$SOURCE_DIR/tests/cli/similarity_class.sh"

reference=$SOURCE_DIR/solutions/apple/NewtonsApple.cpp
scaffold_class class "$reference"
for s in kim lee; do mkdir -p "class/$s" && cp "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" "class/$s/"; done
# pia got as far as two of the five places, in code of her own: what is hers is a few short pieces between the
# starter's.
mkdir -p class/pia
perl -0pe 's/SIMLAB_TODO\("set the initial state[^\n]*/State s = model.system.realizeTopology();\n    model.apple.setOneQ(s, 0, scene.dropHeight);\n    model.apple.setOneU(s, 0, 0);\n    return s;/;
           s/SIMLAB_TODO\("make the integrator[^\n]*/auto integ = simlab::integratorNamed(run.integrator, model.system, run.dt);\n    if (run.fixedStep) {\n        integ->setFixedStepSize(run.dt);\n    } else {\n        integ->setAccuracy(run.accuracy);\n    }\n    return integ;/' \
  "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" >class/pia/NewtonsApple.cpp
copy() {  # copy NAME OF PERL: NAME, a copy of OF's file made by the perl program
  mkdir -p "class/$1" && perl -0pe "$3" "class/$2/NewtonsApple.cpp" >"class/$1/NewtonsApple.cpp"
  cmp -s "class/$2/NewtonsApple.cpp" "class/$1/NewtonsApple.cpp" && fail "the copy $1 changed nothing"
}
# The starter's names (parameters, locals of simulate) and the student's own, renamed throughout.
starter_names='s/\bmodel\b/mdl/g; s/\bscene\b/sc/g; s/\bstate\b/st/g; s/\bintegrator\b/integ/g; s/\brun\b/opts/g;
               s/\brecorder\b/rec/g; s/\bstepper\b/ts/g; s/\binitial\b/s0/g; s/\bk\b/i/g;'
own_names='s/\bappleBody\b/body/g; s/\bchoice\b/answer/g; s/\bp_GA\b/pos/g; s/\bv_GA\b/vel/g; s/\bR_GF\b/R1/g;
           s/\bR_AM\b/R2/g; s/\benergy\b/e/g; s/\bX_turn\b/X/g;'
no_comments='s|[ \t]*//[^\n]*||g;'
# The last function first, and sample() after simulate().
reorder='s/\A(.*?\n)(void buildModel.*?)(simlab::RunSettings cheapestSettings\(\) \{.*?\n\}\n)/$1$3\n$2/s;
         s/(Sample sample\(.*?\n\}\n)\n(void simulate\(.*?\n\}\n)/$2\n$1/s;'
copy copy ann 's|// |// note: |g'
copy renamed ben "$starter_names $own_names"
copy reordered cat "$reorder $starter_names $own_names"
copy kept dan "$no_comments $own_names"
copy starter eli "$starter_names"
copy sly pia "$no_comments $starter_names s/\binteg\b/it/g; s/\bs\b/x/g;"
# quin wrote every place in a line or two of her own: short pieces between the starter's, each shorter than a run
# sim_c++ counts (24 tokens) once the starter's lines around it are gone.
mkdir -p class/quin
perl -0pe 's/SIMLAB_TODO\("build the model[^\n]*/model.apple = MobilizedBody::Slider(model.matter.Ground(), Transform(Rotation(Pi \/ 2, ZAxis), Vec3(0)),\n        Body::Rigid(MassProperties(scene.mass, Vec3(0), UnitInertia::sphere(scene.radius))), Transform(Rotation(Pi \/ 2, ZAxis), Vec3(0)));\n    Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity, 0));/;
           s/SIMLAB_TODO\("set the initial state[^\n]*/State s = model.system.realizeTopology();\n    model.apple.setOneQ(s, 0, scene.dropHeight);\n    return s;/;
           s/SIMLAB_TODO\("make the integrator[^\n]*/auto i = simlab::integratorNamed(run.integrator, model.system, run.dt);\n    i->setAccuracy(run.accuracy);\n    if (run.fixedStep) i->setFixedStepSize(run.dt);\n    return i;/;
           s/SIMLAB_TODO\("sample the time[^\n]*/model.system.realize(state, Stage::Dynamics);\n    return {state.getTime(), model.apple.getOneQ(state, 0), model.apple.getOneU(state, 0), model.system.calcEnergy(state)};/;
           s/SIMLAB_TODO\("explicit Euler[^\n]*/simlab::RunSettings r;\n    r.integrator = "ExplicitEuler";\n    r.fixedStep = true;\n    r.dt = 0.01;\n    return r;/' \
  "$SOURCE_DIR/starter/apple/NewtonsApple.cpp" >class/quin/NewtonsApple.cpp
copy quip quin "$no_comments $starter_names s/\bs\b/x/g; s/\br\b/best/g;"
# ann's copy spelt as the compiler reads alike: its braces and brackets as digraphs, its logic in words, and a
# backslash-newline inside every return and every state (a copy of the copy, so of ann's too).
copy spelt copy "$no_comments"' s/\{/<%/g; s/\}/%>/g; s/\[/<:/g; s/\]/:>/g; s/&&/and/g; s/\|\|/or/g; s/!=/not_eq/g;
                                s/\breturn\b/ret\\\nurn/g; s/\bstate\b/st\\\nate/g;'
grep -q 'cheapestSettings() {' <(head -40 class/reordered/NewtonsApple.cpp) || fail "the reordered copy is in its first order"

run_capture labelled "${SIMLAB_MEASURED:-$SIMLAB}" similarity apple class -o out
test "$(status_of labelled)" -eq 0 || fail "similarity failed: $(cat labelled.err)"
# The flagged pairs, each as "a b" in name order.
grep -E '^ +[0-9]+ %  ' labelled.out | awk '{ a = $(NF - 2); b = $(NF - 1); print (a < b ? a " " b : b " " a) }' | sort >flagged
printf '%s\n' "ann copy" "ben renamed" "cat reordered" "dan kept" "eli starter" "pia sly" "quin quip" "ann spelt" \
  "copy spelt" | sort >copies
pairs=$(( $(find class -mindepth 1 -maxdepth 1 -type d | wc -l) * ($(find class -mindepth 1 -maxdepth 1 -type d | wc -l) - 1) / 2 ))
found=$(comm -12 flagged copies | wc -l)
read -r precision recall < <(awk -v f="$(wc -l <flagged)" -v t="$found" -v c="$(wc -l <copies)" \
  'BEGIN { printf "%.2f %.2f\n", f ? t / f : 1, t / c }')
echo "similarity on the labelled class: $pairs pairs, $(wc -l <copies) of them copies; flagged $(wc -l <flagged), of them $found copies: precision $precision, recall $recall"
echo "missed: $(comm -13 flagged copies | paste -sd, -); flagged honest: $(comm -23 flagged copies | paste -sd, -)"
check "every copy is flagged: renamed, reordered, the starter kept or renamed (recall 1)" test "$recall" = 1.00
check "no honest pair is flagged (precision 1)" test "$precision" = 1.00
check "each flagged pair is shown side by side" bash -c "test \$(grep -c 'class=\"pair\"' out/similarity.html) -eq $(wc -l <flagged)"
finish
