// A project's lab program (the course's side): runs the model written in Project.cpp with its declared
// parameters, changed by --set NAME=VALUE, prints its table as it goes and writes the results file. It also draws
// the model's schematic (--schematic), lists the parameters (--parameters) and computes the answer to the
// project's question (--answer).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include "biosim/program/course.h"
#include "biosim/program/schematic.h"
#include "simlab/reproducible_math.h"
#include "simlab/cli_checks.h"
#include "simlab/digits.h"
#include "simlab/integrators.h"
#include "simlab/messages.h"
#include "simlab/plot.h"
#include "simlab/program.h"
#include "simlab/replay.h"
#include "simlab/results_table.h"
#include "simlab/todo.h"

namespace {

using biosim::Declaration;
using biosim::Parameters;

struct Options {
    simlab::ProgramOptions program;
    std::vector<std::string> settings;  ///< --set NAME=VALUE, as given
    bool schematic = false;
    bool listParameters = false;
    bool answer = false;
    double maxEvaluations = 0;  ///< --trade's cost cap per run; 0: the reference run's own evaluations
};

Parameters parametersFrom(const Declaration& d, const Options& o) {
    std::map<std::string, double> changes;
    for (const std::string& text : o.settings) {
        const auto [name, value] = biosim::parseSetting(text);
        changes[name] = value;
    }
    return biosim::resolve(d, changes);
}

std::vector<std::string> headerOf(const Declaration& d) {
    std::vector<std::string> columns{"time"};
    for (const biosim::Column& c : d.columns) columns.push_back(c.name);
    return columns;
}

int listParameters(const Declaration& d) {
    std::printf("%s: %s\n\n%-10s %-8s %12s %12s %12s  %s\n", d.program.c_str(), d.title.c_str(), "parameter", "unit",
                "default", "min", "max", "meaning");
    for (const biosim::Parameter& p : d.parameters) {
        std::printf("%-10s %-8s %12.6g %12.6g %12.6g  %s\n", p.name.c_str(), p.unit.c_str(), p.value, p.min, p.max,
                    p.meaning.c_str());
    }
    if (!d.rules.empty()) {
        std::printf("\nrules\n");
        for (const biosim::Rule& r : d.rules) std::printf("  %s\n", r.meaning.c_str());
    }
    std::printf("\n%-10s %-8s  %s\n", "column", "unit", "meaning");
    for (const biosim::Column& c : d.columns) {
        std::printf("%-10s %-8s  %s%s\n", c.name.c_str(), c.unit.c_str(), c.meaning.c_str(), c.constant ? " (constant)" : "");
    }
    return 0;
}

int drawSchematic(const Declaration& d, const Parameters& p, const Options& o) {
    biosim::Model model;
    biosim::buildModel(p, model);
    const biosim::Schematic schematic =
        biosim::schematicOf(model, biosim::initialState(p, model), d.title);
    const std::string base = d.program;
    const std::string dot = biosim::treeDot(schematic);
    auto write = [](const std::string& path, const std::string& text) {
        std::ofstream out(path, std::ios::binary);
        if (!(out << text)) throw std::runtime_error("cannot write " + path);
    };
    write(base + "-tree.dot", dot);
    write(base + "-t0.svg", biosim::pictureSvg(schematic));
    std::printf("Wrote %s-tree.dot and %s-t0.svg (the model at t = 0)\n", base.c_str(), base.c_str());
    write(base + "-tree.svg", biosim::renderSvg(dot));
    std::printf("Wrote %s-tree.svg (the multibody tree)\n", base.c_str());
    (void)o;
    return 0;
}

/// The run's figure, where the declaration claims that the energy is conserved for these parameters: how well it
/// was, against the energy the motion exchanges (or, if nothing moved, against the energy itself).
void reportEnergy(const Declaration& d, const Parameters& p, const biosim::Observed& observed) {
    if (!d.claims.energyConserved || observed.time.empty()) return;
    for (const auto& [name, value] : d.claims.energyWhen) {
        if (p[name] != value) return;
    }
    const biosim::EnergyBalance b = biosim::energyBalance(observed);
    const bool moved = b.exchanged > 0;
    const double scale = moved ? b.exchanged : std::abs(b.initial);
    if (!std::isfinite(b.drift) || !std::isfinite(scale)) {
        throw std::runtime_error("the energy is not finite: the run broke (see --accuracy, --integrator)");
    }
    if (!(scale > 0)) {
        // Nothing moved and the energy is zero: the figure is the rest itself, which the exact solution keeps.
        double change = 0;
        for (std::size_t k = 0; k < observed.time.size(); ++k) {
            for (std::size_t i = 0; i < observed.q[k].size(); ++i) change = std::max(change, std::abs(observed.q[k][i] - observed.q[0][i]));
            for (std::size_t i = 0; i < observed.u[k].size(); ++i) change = std::max(change, std::abs(observed.u[k][i] - observed.u[0][i]));
        }
        if (change == 0) {
            std::printf("At rest, as the exact solution is: every q and u kept its value at t = 0 exactly (%.1f accurate "
                        "digits)\n", simlab::kMaxDigits);
        } else {
            std::printf("Energy: the energy is zero and does not move, but q or u changed by %.3g: no figure to give\n",
                        change);
        }
        return;
    }
    // The energy sums kinetic and potential terms of up to |V(0)| + the exchange: where they dwarf the scale, a
    // double's 15.9 digits of them leave fewer of the change, and no figure can claim more than that.
    const double terms = std::abs(observed.potential.front()) + observed.kinetic.front() + b.exchanged;
    const double kept = std::max(0.0, 15.9 - std::log10(terms / scale));
    const double measured = b.drift > 0 ? -std::log10(b.drift / scale) : simlab::kMaxDigits;
    const double digits = std::min({simlab::kMaxDigits, measured, kept});
    std::printf("Energy conserved to %.1f accurate digits: its largest change, %.3g J, against %s, %.3g J\n",
                std::max(0.0, digits), b.drift, moved ? "the energy the motion exchanges" : "the energy (nothing moved)",
                scale);
    if (kept < 12) {
        std::printf("Note: the energy sums terms of up to %.3g J that cancel, so rounding leaves about %.1f of its "
                    "digits against that scale%s\n",
                    terms, kept, measured > kept ? " (a smaller change cannot be seen)" : "");
    }
}

// Every declared column against time, one panel per unit (angles together, speeds together, the energy), `how`
// saying what ran. A project has no exact solution to lay over its run.
simlab::Plot projectPlot(const Declaration& d, const std::string& how, const std::vector<std::vector<double>>& rows) {
    simlab::Plot plot;
    plot.title = d.program + ": " + d.title + " - " + how;
    std::vector<std::string> units;
    for (const biosim::Column& c : d.columns) {
        if (std::find(units.begin(), units.end(), c.unit) == units.end()) units.push_back(c.unit);
    }
    for (std::size_t u = 0; u < units.size(); ++u) {
        std::vector<simlab::PlotCurve> curves;
        for (std::size_t c = 0; c < d.columns.size(); ++c) {
            if (d.columns[c].unit != units[u]) continue;
            simlab::PlotCurve curve(d.columns[c].name + " (" + d.columns[c].meaning + ")");
            for (const std::vector<double>& row : rows) curve.x.push_back(row[0]), curve.y.push_back(row[c + 1]);
            curves.push_back(curve);
        }
        plot.panels.emplace_back(u + 1 == units.size() ? "time t (s)" : "", units[u], curves);
    }
    return plot;
}

void drawRequestedPlot(const Declaration& d, const Options& o, const std::string& how,
                       const std::vector<std::vector<double>>& rows) {
    if (o.program.plot.empty()) return;
    simlab::drawPlot(projectPlot(d, how, rows), o.program.plot);
    std::printf("Plot drawn in %s\n", o.program.plot.c_str());
}

int runOnce(const Declaration& d, const Parameters& p, const Options& o) {
    const simlab::RunSettings& run = o.program.run;
    simlab::ResultsTable table(headerOf(d), o.program.output, o.program.quiet ? nullptr : &std::cout);
    std::printf("%s: %s; %s\n", d.program.c_str(), d.title.c_str(), simlab::describeProgramRun(run).c_str());
    std::fflush(stdout);
    biosim::ObserveHooks hooks;
    std::function<void()> finishAnimation;
    std::unique_ptr<simlab::ReplayRecorder> replay;
    hooks.afterBuild = [&](biosim::Model& m) {
        if (o.program.animate) finishAnimation = simlab::attachVisualizer(m.system, 1.0 / 30, 0.02);
        if (!o.program.replay.empty()) replay = std::make_unique<simlab::ReplayRecorder>(m.system, 1.0 / 30);
    };
    hooks.afterRun = [&] {
        if (finishAnimation) finishAnimation();
    };
    simlab::Progress progress(d.program, run.finalTime);
    std::vector<std::vector<double>> rows;  // for the plot and the replay
    hooks.onRow = [&](double t, const std::vector<double>& row) {
        progress.at(t);
        std::vector<double> values{t};
        values.insert(values.end(), row.begin(), row.end());
        table.add(values);
        if (!o.program.plot.empty() || !o.program.replay.empty()) rows.push_back(values);
    };
    const biosim::Observed observed = biosim::observe(d, p, run, hooks);
    std::printf("\nResults written to %s (%s, %d steps; the model has %d degrees of freedom)\n", table.path().c_str(),
                observed.integrator.method.c_str(), observed.integrator.stepsTaken,
                observed.model.degreesOfFreedom());
    reportEnergy(d, p, observed);
    drawRequestedPlot(d, o, simlab::describeRun(run), rows);
    if (replay) {
        replay->write(o.program.replay, d.program + ": " + d.title, headerOf(d), rows);
        std::printf("Replay written to %s (open it in a web browser)\n", o.program.replay.c_str());
    }
    return 0;
}

int runTrade(const Declaration& d, const Parameters& p, const Options& o) {
    using Clock = std::chrono::steady_clock;
    // No exact solution is known for a project in general: digits are measured against the same model run with
    // Runge-Kutta-Merson at accuracy 1e-13, whose own error is far below what the table shows, in every generalized
    // coordinate and speed at the final time (see biosim::agreementDigits).
    simlab::RunSettings best = o.program.run;
    best.integrator = "RungeKuttaMerson";
    best.accuracy = 1e-13;
    best.fixedStep = false;
    simlab::tellUser(d.program + ": --trade: the reference run first (RungeKuttaMerson at accuracy 1e-13, to t = " +
                     simlab::shortNumber(o.program.run.finalTime) + " s)");
    const Clock::time_point began = Clock::now();
    const biosim::Observed reference = biosim::observe(d, p, best);
    const double referenceSeconds = std::chrono::duration<double>(Clock::now() - began).count();
    // The cost cap, in evaluations of the equations of motion: a count, so that which runs are too costly is the
    // same on any machine. A setting that needs more evaluations than the reference run is no bargain: the
    // reference keeps all the digits the table can show, for less.
    const double cap = o.maxEvaluations > 0 ? o.maxEvaluations : reference.integrator.realizations;
    const std::string capText = std::to_string(static_cast<long long>(cap));
    const double perEvaluation = referenceSeconds / std::max(1, reference.integrator.realizations);
    // Conditioning: the parameters as a double holds them are the problem solved. Moving every one by a unit in its
    // last place (two patterns of signs) and running the reference again shows how many digits of q and u at the
    // final time the parameters themselves fix: a chaotic motion, or a start balanced near an unstable rest (the
    // boot upright), fixes fewer than the table's settings can keep, and the line says so.
    double fixedDigits = simlab::kMaxDigits;
    for (const double sign : {1.0, -1.0}) {
        std::map<std::string, double> nudged = p.values();
        double s = sign;
        for (auto& [name, value] : nudged) {
            if (value != 0) value = std::nextafter(value, s * INFINITY);
            s = -s;
        }
        fixedDigits = std::min(fixedDigits, biosim::agreementDigits(biosim::observe(d, Parameters(nudged), best), reference));
    }
    if (fixedDigits < 12) {
        std::printf("Conditioning: a unit in the last place of each parameter changes q and u at t = %g s to %.1f "
                    "digits: the parameters as given fix the motion no further, and digits past that measure the "
                    "integrator on these doubles alone\n",
                    o.program.run.finalTime, fixedDigits);
    }
    const int integrators = static_cast<int>(simlab::integratorNames().size());
    const int runs = integrators * o.program.repeats;
    simlab::tellUser(d.program + ": --trade: " + std::to_string(integrators) + " integrators, " +
                     std::to_string(o.program.repeats) + " runs each, each stopped past " + capText + " evaluations (" +
                     (o.maxEvaluations > 0 ? "--max-evaluations" : "the reference run's; --max-evaluations sets another") +
                     "): at most about " + simlab::durationText(runs * cap * perEvaluation) + " at the reference's pace");
    char figure[96];
    std::snprintf(figure, sizeof figure, "q and u at t = %g s (against accuracy 1e-13)", o.program.run.finalTime);
    // How far the table has come, before each integrator's first run: what is left, read from the pace so far.
    std::string current;
    int started = 0;
    const Clock::time_point tableBegan = Clock::now();
    simlab::printTrade(std::cout, o.program.run, figure, [&](const simlab::RunSettings& run) {
        if (run.integrator != current) {
            current = run.integrator;
            const double elapsed = std::chrono::duration<double>(Clock::now() - tableBegan).count();
            if (started > 0 && elapsed > 2) {
                simlab::tellUser(d.program + ": --trade: " + run.integrator + ", " + std::to_string(started + 1) +
                                 " of " + std::to_string(integrators) + ", about " +
                                 simlab::durationText(elapsed / started * (integrators - started)) + " left");
            }
            ++started;
        }
        biosim::ObserveHooks hooks;
        hooks.afterStep = [cap, &capText](const SimTK::Integrator& integrator) {
            if (integrator.getNumRealizations() > cap) {
                throw simlab::TooCostly("stopped past " + capText + " evaluations at t = " +
                                        simlab::shortNumber(integrator.getTime()) + " s (--max-evaluations)");
            }
        };
        const biosim::Observed observed = biosim::observe(d, p, run, hooks);
        return simlab::TradePoint{biosim::agreementDigits(observed, reference), observed.integrator.stepsTaken,
                                  observed.integrator.realizations};
    }, o.program.repeats, d.program);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    simlab::useReproducibleMath(argv);
    std::string program = argc > 0 ? argv[0] : "project";
    if (const std::size_t slash = program.rfind('/'); slash != std::string::npos) program = program.substr(slash + 1);
    return simlab::runGuarded(program, [&] {
        // --help (and --version) work even before declare() is written: a new project's first look at its program.
        bool help = false;
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            help = help || arg == "--help" || arg == "-h" || arg == "--version";
        }
        Declaration d;
        try {
            d = biosim::declare();
            biosim::checkDeclaration(d);
        } catch (const simlab::NotDoneYet& e) {
            if (!help) throw;
            d.program = program;
            d.title = program + " (declare() is not written yet: " + e.file() + ":" + std::to_string(e.line()) + ")";
        }
        Options o;
        o.program.run = d.run;
        o.program.output = d.program + "Results.txt";

        CLI::App app{d.title + "\nA biosimulation project: its parameters are set with --set NAME=VALUE (see --parameters).",
                     program};
        simlab::addProgramOptions(app, o.program);
        app.add_option("--set", o.settings, "change a declared parameter, e.g. --set g=0 (repeatable)")
            ->type_name("NAME=VALUE");
        app.add_flag("--parameters", o.listParameters, "list the parameters (units, defaults, ranges) and columns");
        app.add_flag("--schematic", o.schematic,
                     "draw the model: <program>-tree.svg (the multibody tree) and <program>-t0.svg (the model at t = 0)");
        app.add_flag("--answer", o.answer, "compute the number that answers the project's question");
        app.add_option("--max-evaluations", o.maxEvaluations,
                       "with --trade: the evaluations of the equations of motion one run may take before it is "
                       "stopped and its row says too costly (default: the reference run's own, at accuracy 1e-13)")
            ->check(simlab::between(100.0, 1e10));
        if (const int status = simlab::parseCommandLine(app, argc, argv); status >= 0) return status;

        if (const int status = simlab::checkRunSettings(program, o.program.run); status >= 0) return status;
        Parameters p;
        try {
            p = parametersFrom(d, o);
        } catch (const std::invalid_argument& e) {
            // A --set the declaration does not allow is a usage error, like any other option's.
            std::cerr << program << ": error: " << e.what() << " (see " << program << " --parameters)\n";
            return 2;
        }
        if (o.listParameters) return listParameters(d);
        if (o.schematic) return drawSchematic(d, p, o);
        if (o.answer) {
            const double value = biosim::answer(p);
            std::printf("%s: the answer to the project's question is %.6g\n", d.program.c_str(), value);
            return std::isfinite(value) ? 0 : 1;
        }
        if (!o.program.from.empty()) {
            drawRequestedPlot(d, o, "from " + o.program.from, simlab::readResults(o.program.from, headerOf(d)));
            return 0;
        }
        return o.program.trade ? runTrade(d, p, o) : runOnce(d, p, o);
    });
}
