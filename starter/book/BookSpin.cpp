// The spinning book, simulated with Simbody.
//
// HOW TO USE THIS FILE
// This lab you write the simulation yourself; the file gives you its shape. Every place where you write code
// holds a line
//
//     SIMLAB_TODO("what to write here");
//
// and the program stops at the first one it reaches. Replace each with your code. Your answers to the handout's
// questions go in BookAnswers.toml, beside this file. Rebuild and run with
//
//     cmake --build build && build/bin/book --spin min     check your work with   build/bin/simlab check book
//
// THE PHYSICS
// A uniform book of mass m and edges Lx, Ly, Lz (height, width, thickness) turns freely about its center: no
// torque acts on it. Its central principal axes run along its edges. With no torque, Euler's equations
//     Ixx wx' = (Iyy - Izz) wy wz,   Iyy wy' = (Izz - Ixx) wz wx,   Izz wz' = (Ixx - Iyy) wx wy
// govern its angular velocity; Simbody forms and solves them for you from the model.
//
// NAMES
// G is Ground, B the book. w_GB is B's angular velocity in G; w_B is that vector expressed in B; H_B the book's
// angular momentum about its center, expressed in B; R_GB rotates B's components into G's. The contract, with
// the Scene, Sample and Model types, is book/BookSpin.h.
#include "book/BookSpin.h"

#include "simlab/integrators.h"
#include "simlab/todo.h"

namespace book {

using namespace SimTK;

void buildModel(const Scene& scene, Model& model) {
    // 1. The model: one body for the book, with the mass properties of a uniform brick of scene.mass and
    //    scene.dimensions, centered on the body's origin; and the mobilizer that lets it turn, in every
    //    direction, about that center and nothing else. Store the mobilized body in model.book.
    //    Look up UnitInertia::brick in Simbody's documentation: read carefully what its arguments are.
    SIMLAB_TODO("build the model: the book's body and the mobilizer that lets it turn about its center");
}

State initialState(const Scene& scene, const Model& model) {
    // 2. The initial state: the book's axes along Ground's, turning at scene.w_B0 (rad/s, in the book's axes).
    //    Mobilized bodies have setUToFit... functions that set the speeds from a velocity you give.
    SIMLAB_TODO("set the initial state: the book spinning at scene.w_B0");
}

std::unique_ptr<Integrator> makeIntegrator(const Model& model, const simlab::RunSettings& run) {
    // 3. The integrator, as in the earlier labs.
    SIMLAB_TODO("make the integrator named in run, at run.accuracy");
}

Sample sample(const Model& model, const State& state) {
    // 4. The sampled quantities: w_B, H_B, H_G, |H| and the kinetic energy K. Simbody gives the book's angular
    //    velocity expressed in Ground (getBodyAngularVelocity); the handout wants it in the book's own axes. The
    //    body's mass properties (getBodyMassProperties) hold its inertia about its origin, in its own axes.
    SIMLAB_TODO("sample w, H (in the book and in Ground), |H| and K from the state");
}

void simulate(const Model& model, Integrator& integrator, const State& initial, const simlab::RunSettings& run,
              simlab::Recorder<Sample>& recorder) {
    // 5. The stepping loop, sampling at t = 0 and at every run.sampleTime(k), as in the earlier labs.
    SIMLAB_TODO("step to the final time, sampling every dt");
}

simlab::RunSettings cheapestSettings() {
    // The trade (handout, section 6): the cheapest setting that keeps 8 digits of w_B on the trade question's
    // tumbling spin. Measure it: `build/bin/simlab study trade book --question` (in the student bundle, add
    // `--file BookSpin.cpp`). Return a RunSettings with integrator and accuracy set (or fixedStep = true and the
    // step in dt).
    SIMLAB_TODO("the cheapest setting that keeps 8 digits of w_B on the question's tumbling spin");
}

}  // namespace book
