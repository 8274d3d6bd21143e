// `simlab study long-run`: the book's or the baby boot's long-run view, which the lab's study program
// (simlab/long_run.h) runs whole: it runs each setting, writes the CSV and the figure, and prints the table. Of the
// reference solution, the command hands over to the program; of a student's file, the program built from it runs
// in grading's sandbox, where gnuplot does not run: it writes the CSV and prints the table there, the CSV is read
// back as data, and the figure is drawn here from it.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string_view>

#include "internal.h"
#include "simlab/build/manifest.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"
#include "simlab/isolation/process.h"

namespace simlab::study {

namespace {

/// The lab `o` names, checked: the book or the baby boot.
const engine::Assignment& longRunLab(const engine::Manifest& manifest, const LongRunOptions& o) {
    if (o.lab != "book" && o.lab != "biosim") {
        throw engine::UsageError("the long-run view is the book's or the baby boot's: book or biosim, not '" +
                                 engine::printable(o.lab) + "'");
    }
    return manifest.find(o.lab);
}

/// The view's own options, after the program and `long-run`.
std::vector<std::string> viewArguments(const LongRunOptions& o, const std::string& output) {
    std::vector<std::string> args = {"--output", output};
    if (o.finalTime > 0) args.insert(args.end(), {"--final-time", std::to_string(o.finalTime)});
    if (o.quick) args.push_back("--quick");
    if (!o.plots) args.push_back("--no-plots");
    return args;
}

/// A cell of the view's CSV as it writes them: a finite number, or a plain word or phrase (an integrator, a
/// setting, "the reference") that no spreadsheet reads as a formula.
bool plainCell(const std::string& cell) {
    if (cell.empty() || cell.size() > 80) return false;
    char* end = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    if (end == cell.c_str() + cell.size()) return std::isfinite(value);
    return std::isalnum(static_cast<unsigned char>(cell[0])) &&
           std::all_of(cell.begin(), cell.end(), [](char c) {
               return std::isalnum(static_cast<unsigned char>(c)) || std::string_view(" ._()+-").find(c) != std::string_view::npos;
           });
}

/// One curve of the view's figure: a setting's samples.
struct Curve {
    std::string setting;  ///< "RungeKuttaMerson, accuracy 1e-06"
    bool fixedStep = false;
    std::vector<double> t, drift, digits;
};

/// The view's CSV, as a program built from a student's file wrote it, read as data: a header naming the columns
/// the figure reads, then rows of plain cells (plainCell), at most 100000. The curves, a setting each in the order
/// the rows first name it; empty, with `why`, for a file that is not what the view writes.
std::vector<Curve> readLongRunCsv(const std::string& text, std::string& why) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> cells;
        std::istringstream split(line);
        for (std::string cell; std::getline(split, cell, ',');) cells.push_back(cell);
        rows.push_back(std::move(cells));
    }
    if (rows.size() < 2 || rows.size() > 100001) {
        why = "it has " + std::to_string(rows.size()) + " lines";
        return {};
    }
    const std::vector<std::string>& header = rows.front();
    if (!std::all_of(header.begin(), header.end(), plainCell)) {
        why = "its header is not one the view writes";
        return {};
    }
    auto column = [&](const char* name) {
        const auto at = std::find(header.begin(), header.end(), name);
        return at == header.end() ? header.size() : static_cast<std::size_t>(at - header.begin());
    };
    const std::size_t integrator = column("integrator"), stepping = column("stepping"), t = column("t_s"),
                      drift = column("energy_drift"), digits = column("trajectory_digits");
    if (std::max({integrator, stepping, t, drift, digits}) >= header.size()) {
        why = "its header lacks a column the figure reads";
        return {};
    }
    std::vector<Curve> curves;
    for (std::size_t r = 1; r < rows.size(); ++r) {
        const std::vector<std::string>& row = rows[r];
        if (row.size() != header.size() || !std::all_of(row.begin(), row.end(), plainCell)) {
            why = "line " + std::to_string(r + 1) + " is not one the view writes";
            return {};
        }
        if (std::find(std::begin(kIntegrators), std::end(kIntegrators), row[integrator]) == std::end(kIntegrators)) {
            why = "line " + std::to_string(r + 1) + " names no integrator";
            return {};
        }
        const std::string setting = row[integrator] + ", " + row[stepping];
        auto curve = std::find_if(curves.begin(), curves.end(), [&](const Curve& c) { return c.setting == setting; });
        if (curve == curves.end()) {
            if (curves.size() == 16) {
                why = "it has more settings than the view runs";
                return {};
            }
            curves.push_back({setting, row[stepping].rfind("fixed step", 0) == 0, {}, {}, {}});
            curve = curves.end() - 1;
        }
        curve->t.push_back(std::strtod(row[t].c_str(), nullptr));
        curve->drift.push_back(std::strtod(row[drift].c_str(), nullptr));
        curve->digits.push_back(std::strtod(row[digits].c_str(), nullptr));
    }
    return curves;
}

/// The figure of a student's file, drawn here from its CSV: a program built from a student's file runs in
/// grading's sandbox, where gnuplot does not run. As the view draws the reference solution's: the energy's drift
/// over the trajectory's digits as an error (10^-digits), both against time on log-log axes, a curve per setting
/// (dashed: a fixed step). Returns an empty string when drawn, else why not.
std::string drawLongRunFigure(const std::vector<Curve>& curves, const fs::path& svg, const std::string& lab,
                              const std::string& file) {
    const std::string gnuplot = "/usr/bin/gnuplot";  // Debian's gnuplot-nox (scripts/install-deps)
    if (!fs::exists(gnuplot)) return "gnuplot is not installed (scripts/install-deps installs gnuplot-nox)";
    auto quoted = [](const std::string& text) {  // a gnuplot string in single quotes, where only '' is special
        std::string out = "'";
        for (const char c : engine::printable(text)) out += c == '\'' ? std::string("''") : std::string(1, c);
        return out + "'";
    };
    double finalTime = 0;
    for (const Curve& c : curves) finalTime = std::max(finalTime, c.t.empty() ? 0.0 : c.t.back());
    char title[512];
    std::snprintf(title, sizeof title, "%s, %s: energy digits are not trajectory digits (%g s)", lab.c_str(),
                  engine::printable(fs::path(file).filename().string()).c_str(), finalTime);
    engine::TempDir scratch("simlab-long-run-figure-");
    std::ostringstream gp;
    gp << "set terminal svg size 960,720 font 'sans,11' background '#ffffff'\nset termoption noenhanced\n"
       << "set output 'figure.svg'\nset grid\nset key below\nset datafile missing 'NaN'\n"
       << "set logscale xy\nset autoscale xfix\nset format y '%.0e'\nset xlabel 't (s)'\n"
       << "set lmargin at screen 0.11\nset rmargin at screen 0.96\n";
    for (std::size_t k = 0; k < curves.size(); ++k) {
        for (const char* panel : {"e", "d"}) {
            gp << "$" << panel << k << " << EOD\n";
            const Curve& c = curves[k];
            for (std::size_t i = 0; i < c.t.size(); ++i) {
                const double y = panel[0] == 'e' ? std::max(c.drift[i], 1e-16) : std::pow(10.0, -c.digits[i]);
                if (c.t[i] > 0 && y > 0 && std::isfinite(y)) gp << c.t[i] << ' ' << y << '\n';
            }
            gp << "EOD\n";
        }
    }
    gp << "set multiplot layout 2,1 title " << quoted(title) << "\n";
    for (const char* panel : {"e", "d"}) {
        gp << "set ylabel " << quoted(panel[0] == 'e' ? "energy drift |E(t) - E(0)| / scale" : "trajectory error")
           << "\nplot ";
        for (std::size_t k = 0; k < curves.size(); ++k) {
            gp << (k ? ", \\\n     " : "") << "$" << panel << k << " using 1:2 with lines linewidth 2 lc " << k + 1
               << (curves[k].fixedStep ? " dashtype 2" : "") << " title " << quoted(curves[k].setting);
        }
        gp << "\n";
    }
    gp << "unset multiplot\nset output\n";
    engine::writeFileAtomically(scratch.path() + "/figure.gp", gp.str());
    try {
        isolation::runTool({gnuplot, "figure.gp"}, scratch.path());
    } catch (const std::runtime_error& e) {
        return engine::printable(e.what());
    }
    engine::writeFileAtomically(svg.string(), engine::readFile(scratch.path() + "/figure.svg"));
    return "";
}

}  // namespace

std::vector<std::string> longRunCommand(const LongRunOptions& o, int cores) {
    const engine::Manifest manifest = engine::loadManifest();
    const engine::Assignment& a = longRunLab(manifest, o);
    if (a.studyProgramPath.empty()) {
        throw engine::UsageError("no long-run view of " + o.lab +
                                 "'s reference solution, which is not in this tree: follow your own file with --file "
                                 "(e.g. --file " + engine::printable(a.starter) + ")");
    }
    ensureStudiesBuilt(manifest, {&a}, false, cores);
    std::vector<std::string> args = {a.studyProgramPath, "long-run"};
    const std::vector<std::string> view = viewArguments(o, o.output);
    args.insert(args.end(), view.begin(), view.end());
    return args;
}

int runLongRunOfFile(const LongRunOptions& o, const CommandLine& command) {
    const engine::Manifest manifest = engine::loadManifest();
    const engine::Assignment& a = longRunLab(manifest, o);
    if (a.id == "biosim") {
        throw engine::UsageError("--file follows the book's file: biosim's long-run view is the baby boot's (simlab "
                                 "study long-run biosim)");
    }
    if (a.studyObjects.empty()) throw engine::UsageError("this copy of simlab has no long-run view of " + a.id);
    ensureStudiesBuilt(manifest, {&a}, true, command.cores);
    const StudyProgram program = buildStudyOfFile(manifest, a, o.file, command);
    const fs::path output = fs::absolute(o.output);
    fs::create_directories(output);

    // The program writes in a folder of its own, which comes back; the folder it is told of is that one, and its
    // lines name the output folder instead.
    engine::TempDir scratch("simlab-long-run-");
    isolation::ProcessRequest request;
    request.argv = {program.path, "long-run"};
    LongRunOptions table = o;
    table.plots = false;  // the figure is drawn here
    const std::vector<std::string> view = viewArguments(table, scratch.path());
    request.argv.insert(request.argv.end(), view.begin(), view.end());
    request.env = isolation::childEnvironment({"LC_ALL=C"});
    request.workDir = scratch.path();
    request.isolate = true;
    request.studentCode = true;
    request.readOnlyPaths = {program.folder->path()};
    request.limits.cpuSeconds = 4 * 3600;  // a net: the view's settings end at its final time
    request.limits.wallSeconds = 12 * 3600;
    request.limits.memoryMiB = 8192;
    request.limits.outputKiB = 1 << 14;
    request.limits.fileMiB = 64;
    request.limits.processes = 16;  // gnuplot, which draws the figure
    request.keepOutput = 0;
    request.onOutputLine = [&](const std::string& line) {
        std::string shown = engine::printable(line);
        for (std::size_t at = shown.find(scratch.path()); at != std::string::npos;
             at = shown.find(scratch.path(), at + output.string().size())) {
            shown.replace(at, scratch.path().size(), output.string());
        }
        std::cout << shown << '\n' << std::flush;
    };
    const isolation::ProcessResult result = isolation::runProcess(request);
    if (!result.started) throw std::runtime_error("cannot run " + program.path + ": " + result.error);

    // The CSV it wrote, read as data and written again; the figure drawn here from it.
    const std::string name = a.id + "-long-run.csv";
    const fs::path made = fs::path(scratch.path()) / name;
    std::string why = "the view wrote none";
    std::vector<Curve> curves;
    if (fs::is_regular_file(fs::symlink_status(made))) curves = readLongRunCsv(engine::readFile(made.string()), why);
    if (!curves.empty()) {
        engine::writeFileAtomically((output / name).string(), engine::readFile(made.string()));
        if (o.plots) {
            const std::string figure = a.id + "-long-run.svg";
            const std::string failed = drawLongRunFigure(curves, output / figure, a.id, o.file);
            std::cout << (failed.empty() ? "Drawn from it: " + figure + " (energy drift over trajectory error)"
                                         : "No figure: " + failed)
                      << '\n';
        }
    } else if (result.exitedCleanly()) {
        std::cout << "Left out " << name << ": " << why << '\n';
    }
    if (result.cpuTimeout || result.wallTimeout) {
        throw std::runtime_error("the long run of " + engine::printable(o.file) + " ran past its time net");
    }
    if (result.signal != 0) {
        throw std::runtime_error("the long run of " + engine::printable(o.file) + " crashed (" +
                                 isolation::signalName(result.signal) + ")");
    }
    if (result.outputLimit || result.memoryLimit || result.diskLimit) {
        throw std::runtime_error("the long run of " + engine::printable(o.file) + " was stopped: it " +
                                 (result.outputLimit   ? "printed more than a long-run view prints"
                                  : result.memoryLimit ? "took more memory than its limit"
                                                       : "wrote more than its limit"));
    }
    return result.exitCode == 0 && !curves.empty() ? 0 : 1;
}

}  // namespace simlab::study
