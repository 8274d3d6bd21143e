// The work-precision study's measuring side: what each of Simbody's integrators pays, in steps, evaluations and
// time, for the digits it reaches on a lab's scene, against a reference that does not use Simbody.
//
// Each lab's study program (`<program>-study`, run by `simlab study trade`) lists its scenes as Subjects and hands
// them to studyMain, which runs every integrator at accuracies 1e-1 ... 1e-14 and, for the methods that can take
// fixed steps, a sweep of step sizes, each point under a cost cap, and prints one JSON object per line: the
// subject, then its points. simlab turns them into trade.csv, plots and the table of cheapest settings.
//
// How the cost of integrating is kept apart from the cost of sampling: the integrator reports only at the final
// time, so no sample interval ever cuts a step short. The error along the way is read at the integrator's own
// internal steps (returning after each does not change them), and the time is the fastest of N repeats that
// report only at the end, after the measured run has warmed the caches.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "Simbody.h"
#include <nlohmann/json.hpp>
#include "simlab/digits.h"
#include "simlab/ode_reference.h"

namespace simlab::study {


/// One scene, built and ready to integrate, and how to judge any state of it against the reference.
class Instance {
public:
    virtual ~Instance() = default;
    virtual const SimTK::MultibodySystem& system() const = 0;
    virtual const SimTK::State& initial() const = 0;
    /// Digits to which `state` (realized through Velocity) agrees with the reference at its time: the worst
    /// component, each against its stated scale, never a relative error at a zero.
    virtual double digits(const SimTK::State& state) = 0;
    /// The quantity the motion conserves (its drift is the third measure).
    virtual double conserved(const SimTK::State& state) = 0;
    /// Digits of the figure the lab reports when the run is over (the ground hit's, say); the final state's by
    /// default.
    virtual double finalDigits(const SimTK::State& state) { return digits(state); }
    /// Digits to which `state` agrees with `tighter`, the same scene at the same time run more accurately (what
    /// `study long-run` measures where no reference lasts): the worst generalized coordinate and speed, each
    /// against the larger of its size and 1 in its own unit (1 rad and 1 rad/s for a Pin's).
    virtual double agreementDigits(const SimTK::State& state, const SimTK::State& tighter) {
        double worst = simlab::kMaxDigits;
        for (int i = 0; i < state.getNQ(); ++i) {
            worst = std::min(worst, simlab::accuracyDigits(state.getQ()[i], tighter.getQ()[i], 1.0));
        }
        for (int i = 0; i < state.getNU(); ++i) {
            worst = std::min(worst, simlab::accuracyDigits(state.getU()[i], tighter.getU()[i], 1.0));
        }
        return worst;
    }
};

/// A drift: |change| of the conserved quantity over `scale`, the subject's own size for it (conservedScale). Where the
/// scene gives it no size (at rest, nothing to exchange) a change of nothing is none, and any other past measure.
inline double relativeDrift(double change, double scale) {
    if (scale > 0) return change / scale;
    return change == 0 ? 0.0 : INFINITY;
}

/// A lab's scene in the study.
struct Subject {
    std::string name;               ///< e.g. "book-intermediate"
    std::string figure;             ///< what the digits measure, one line
    /// What the final digits measure, where the lab reports a figure of its own when the run is over (the ground
    /// hit's time and range): the study then gives that figure its own front. Empty: the final state's digits.
    std::string finalFigure;
    std::string conservedName;      ///< e.g. "energy"
    /// The scene has event triggers (the projectile's ground hit): at any fixed step the accuracy localizes them, so
    /// the fixed-step rows name the accuracy they ran at.
    bool events = false;
    double conservedScale = 1;      ///< the drift is the largest |change| over this (relativeDrift)
    double finalTime = 1;           ///< s
    std::string reference;          ///< how the reference is computed, one line
    std::function<double()> referenceDigits;  ///< the reference's own accuracy at the final time, in digits
    std::function<std::unique_ptr<Instance>()> make;
    /// The same scene over-modelled: a Free (or Cartesian, Planar) mobilizer where the scene needs fewer motions,
    /// for `simlab study minimal`; empty where there is none. `overModelled` names it, e.g. "Free (6 dof)".
    std::function<std::unique_ptr<Instance>()> makeOverModelled;
    std::string minimal, overModelled;
    /// The same scene from other starts (a number of it moved in its last place): each point is measured from
    /// `make` and from each of these, and kept at its worst (the fewest digits, the most steps and evaluations), so
    /// that a point that lands well from one start alone does not count as good. Empty: one start.
    std::vector<std::function<std::unique_ptr<Instance>()>> moreStarts;
};

/// A lab's scene in the study from its wire form (the lab's Scene as JSON, as the trade question's data file
/// holds it) and a final time: what `--scene` studies.
using SubjectForScene = std::function<Subject(const nlohmann::json& scene, double finalTime)>;

/// Parses the study program's command line (--quick, --cap, --repeats, --subject, --list, --minimal, --integrators,
/// --fixed-steps-only, --sweep; with `forScene`, --scene and what goes with it: --final-time, --name, --starts,
/// --nudge, --answer-digits), runs the study of `subjects` (or of the scene given, or of one sweep of it, or, with
/// --minimal, each scene minimal and over-modelled side by side) and prints it as JSON lines on stdout (progress
/// goes to stderr). Returns the exit status.
int studyMain(int argc, char** argv, const std::string& lab, const std::vector<Subject>& subjects,
              const SubjectForScene& forScene = nullptr);

}  // namespace simlab::study
