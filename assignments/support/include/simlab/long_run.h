// The long-run view (`simlab study long-run LAB`): one scene of a lab followed for a long time (1000 s by default)
// by an error-controlled method at two accuracies and by fixed-step methods, sampled at log-spaced times, so that a
// student sees that the energy's digits are not the trajectory's, and that a symplectic fixed step (Verlet) keeps
// its energy error bounded where an error-controlled method lets it grow with time.
//
// Each sample is a state the integrator stepped to (interpolation is off), so that the energy read there is that
// of the method's own trajectory, never of an interpolant between its steps.
#pragma once

#include <functional>
#include <string>

#include "simlab/study.h"

namespace simlab::study {

/// How the long-run view judges a run's trajectory.
enum class TrajectoryCheck {
    /// Instance::digits: against the subject's reference, which keeps its digits over the whole run (the book's
    /// Euler equations in long double).
    reference,
    /// Instance::agreementDigits: against the same method run tighter (a tenth of the accuracy, half the fixed
    /// step), for a motion no reference follows that long (the chaotic boot): self-convergence.
    tighterRun,
};

/// A lab's long-run view.
struct LongRunView {
    std::function<Subject(double finalTime)> subject;  ///< the scene followed to a final time, s
    std::string scene;                                 ///< which scene, one line ("the lab's default spin, ...")
    TrajectoryCheck trajectory = TrajectoryCheck::reference;
    double fixedStep = 1e-3;       ///< s, the fixed-step methods' step
    /// The accuracy Verlet's fixed step solves its implicit velocity update to (simlab::fixedStepUsesAccuracy), named
    /// in the table with the step. Tight, so that the step is the time-reversible one it stands for: solved only to
    /// Simbody's default of 1e-3, the book's energy error grows past about 50 s (9.9e-6 of K at 100 s, against
    /// 4.2e-6 from 1e-6 on).
    double fixedStepAccuracy = 1e-9;
    double quickFinalTime = 20;    ///< s, with --quick (for tests: seconds of work, not minutes)
};

/// `<program> long-run [--final-time T] [--quick] [--output DIR] [--no-plots]` (what `simlab study long-run`
/// runs): every setting to the final time, the table on standard output (progress on standard error), and
/// DIR/<lab>-long-run.csv and DIR/<lab>-long-run.svg. Returns the exit status: 0, 1 when a setting failed
/// (the table says where and why), 2 for bad input.
int longRunMain(int argc, char** argv, const std::string& lab, const LongRunView& view);

/// True when the study program's command line asks for the long-run view (its first argument is `long-run`).
bool asksForLongRun(int argc, char** argv);

}  // namespace simlab::study
