# scaffold_class DIR REFERENCE: an apple class of five honest students in DIR, each REFERENCE (the reference solution)
# with two or three edits of their own in the five places the starter leaves to write: a scaffolded lab, where every
# honest solution looks alike. Sourced by the similarity tests.
scaffold_class() {
  local dir=$1 reference=$2 s
  edit() { mkdir -p "$dir/$1"; perl -0pe "$2" "$reference" >"$dir/$1/NewtonsApple.cpp"; }
  # ann: the body's mass set after it is made; the samples inline; the trade's fields in another order
  edit ann 's/const Body::Rigid appleBody\(([^\n]*)\);/Body::Rigid appleBody;\n    appleBody.setDefaultRigidBodyMassProperties($1);/;
            s/const Vec3 p_GA[^\n]*\n[^\n]*v_GA = [^\n]*\n(\s*)return \{[^\n]*/return {state.getTime(), model.apple.getBodyOriginLocation(state)[YAxis],\n$1        model.apple.getBodyOriginVelocity(state)[YAxis], model.system.calcEnergy(state)};/;
            s/(choice.integrator = [^\n]*\n)(\s*choice.fixedStep = true;\n)(\s*choice.dt = 1e-2;\n)/$3$1$2/'
  # ben: the state by updQ and updU; the accuracy after the fixed step, in braces; y and its speed from the Slider
  edit ben 's/model.apple.setOneQ\(state, 0, scene.dropHeight\);/state.updQ()[0] = scene.dropHeight;/;
            s/model.apple.setOneU\(state, 0, 0.0\);/state.updU() = 0;/;
            s/(\s*)integrator->setAccuracy\(run.accuracy\);\n(\s*if \(run.fixedStep\)) ([^\n]*)\n/\n$2 {\n        $3\n    }$1integrator->setAccuracy(run.accuracy);\n/;
            s/p_GA\[YAxis\], v_GA\[YAxis\]/model.apple.getOneQ(state, 0), model.apple.getOneU(state, 0)/'
  # cat: gravity first; the height by setQ; the energy before the positions
  edit cat 's/(\n\s*\/\/ The apple: a uniform)/\n    Force::UniformGravity(model.forces, model.matter, Vec3(0, -scene.gravity, 0));$1/;
            s/\n\s*Force::UniformGravity[^\n]*\n\}/\n}/; s/setOneQ\(state, 0, scene.dropHeight\)/setQ(state, Vector(1, scene.dropHeight))/;
            s/(\s*)(const Vec3 p_GA)/$1const Real energy = model.system.calcEnergy(state);$1$2/; s/model.system.calcEnergy\(state\)\}/energy}/'
  # dan: one transform for both frames; auto; no speed set (it starts at zero)
  edit dan 's/const Rotation R_GF[^\n]*\n[^\n]*R_AM[^\n]*\n(\s*)model.apple = [^\n]*\n[^\n]*\n/const Transform X_turn(Rotation(Pi \/ 2, ZAxis), Vec3(0));$1model.apple = MobilizedBody::Slider(model.matter.Ground(), X_turn, appleBody, X_turn);\n/;
            s/std::unique_ptr<Integrator> integrator =/auto integrator =/; s/\n\s*model.apple.setOneU[^\n]*//'
  # eli: the default state after realizing the topology; accuracy or a fixed step; the trade's step tied to its flag
  edit eli 's/State state = model.system.realizeTopology\(\);/model.system.realizeTopology();\n    State state = model.system.getDefaultState();/;
            s/integrator->setAccuracy\(run.accuracy\);\n(\s*)if \(run.fixedStep\) ([^\n]*)/if (run.fixedStep) $2$1else integrator->setAccuracy(run.accuracy);/;
            s/choice.dt = 1e-2;/choice.dt = choice.fixedStep ? 1e-2 : run.dt;/'
  for s in ann ben cat dan eli; do
    cmp -s "$reference" "$dir/$s/NewtonsApple.cpp" && fail "$s's edits changed nothing"
  done
}
