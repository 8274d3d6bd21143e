// The study in parts, one per lab and integrator, for machines that share OUTPUT (a cluster's job array): each
// part measured into OUTPUT/parts, and trade.csv and the plots assembled from them.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <tuple>

#include "internal.h"
#include "simlab/build/build.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"

namespace simlab::study {

namespace {

/// One part: a lab's study with one integrator, kept in its file.
struct Part {
    const engine::Assignment* lab;
    std::string integrator;
    std::size_t integratorIndex;
    fs::path file;
};

/// What a part is measured with: the study program's bytes and the options that change its points.
std::string keyOf(const StudyOptions& o, const Part& p) {
    engine::Hash h;
    h.addFileContent(p.lab->studyProgramPath).add(p.integrator).add(o.quick ? "quick" : "full");
    h.add(std::to_string(o.maxEvaluations)).add(std::to_string(o.cap)).add(std::to_string(o.repeats));
    return h.hex();
}

/// The part's file, where it holds what `o` would measure; empty where it is missing or measured otherwise.
std::optional<json> kept(const StudyOptions& o, const Part& p) {
    if (!fs::exists(p.file)) return std::nullopt;
    const json j = json::parse(engine::readFile(p.file.string()), nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("lines") || text(j["key"]) != keyOf(o, p))
        return std::nullopt;
    return j;
}

/// Parts `mine` of `parts` measured into their files, --jobs at once, but for those kept; says how many of each.
void measure(const StudyOptions& o, const std::vector<Part>& parts, const std::vector<std::size_t>& mine) {
    std::mutex lock;
    std::atomic<int> measured{0}, reused{0};
    std::string failure;
    forEachInParallel(mine.size(), std::min<int>(o.jobs, static_cast<int>(mine.size())), [&](std::size_t i) {
        const Part& p = parts[mine[i]];
        if (kept(o, p)) {
            ++reused;
            return;
        }
        std::vector<std::string> argv = {p.lab->studyProgramPath, "--integrators", p.integrator};
        if (o.quick) argv.push_back("--quick");
        if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
        if (o.maxEvaluations > 0) argv.insert(argv.end(), {"--max-evaluations", std::to_string(o.maxEvaluations)});
        if (o.repeats > 0) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
        json lines = json::array();
        const auto start = std::chrono::steady_clock::now();
        const int status = runStudyProgram(argv, false, [&lines](const json& j) { lines.push_back(j); });
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::lock_guard<std::mutex> guard(lock);
        if (status != 0) {
            if (failure.empty()) {
                failure = "the study of " + p.lab->id + " with " + p.integrator + " stopped with status " +
                          std::to_string(status);
            }
            return;
        }
        const json part = {{"key", keyOf(o, p)}, {"lab", p.lab->id}, {"integrator", p.integrator}, {"lines", lines}};
        engine::writeFileDurably(p.file.string(), part.dump() + "\n");
        ++measured;
        std::printf("  part %s %s: %zu lines in %.1f s\n", p.lab->id.c_str(), p.integrator.c_str(), lines.size(),
                    seconds);
        std::fflush(stdout);
    });
    std::cout << measured << " part(s) measured, " << reused << " up to date and kept, of "
              << (o.shard.empty() ? "the study's " : "shard " + o.shard + "'s ") << mine.size() << '\n';
    if (!failure.empty()) throw std::runtime_error(failure);
}

/// Each lab's scenes in the order its parts first name them; each scene's points as one run orders them: the
/// accuracy sweeps integrator by integrator, then the fixed steps.
std::vector<SubjectRun> assemble(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs,
                                 const std::vector<Part>& parts) {
    std::vector<SubjectRun> runs;
    for (const engine::Assignment* a : labs) {
        std::vector<SubjectRun> labRuns;
        std::vector<std::vector<std::tuple<int, std::size_t, std::size_t, json>>> keyed;
        for (const Part& p : parts) {
            if (p.lab != a) continue;
            const std::optional<json> part = kept(o, p);
            if (!part) throw std::runtime_error("the part " + p.file.string() + " is missing or unreadable");
            std::size_t current = labRuns.size(), seq = 0;
            for (const json& line : (*part)["lines"]) {
                if (text(line["type"]) == "subject") {
                    current = labRuns.size();
                    for (std::size_t k = 0; k < labRuns.size(); ++k) {
                        if (text(labRuns[k].subject["subject"]) == text(line["subject"])) current = k;
                    }
                    if (current == labRuns.size()) {
                        labRuns.push_back({line, {}, {}});
                        keyed.emplace_back();
                    }
                } else if (text(line["type"]) == "point" && current < labRuns.size()) {
                    keyed[current].emplace_back(text(line["mode"]) == "accuracy" ? 0 : 1, p.integratorIndex, seq++,
                                                line);
                }
            }
        }
        for (std::size_t k = 0; k < labRuns.size(); ++k) {
            std::stable_sort(keyed[k].begin(), keyed[k].end(), [](const auto& x, const auto& y) {
                return std::tie(std::get<0>(x), std::get<1>(x), std::get<2>(x)) <
                       std::tie(std::get<0>(y), std::get<1>(y), std::get<2>(y));
            });
            for (auto& entry : keyed[k]) labRuns[k].points.push_back(std::get<3>(entry));
        }
        runs.insert(runs.end(), labRuns.begin(), labRuns.end());
    }
    return runs;
}

}  // namespace

/// The study in parts, one per lab and integrator, for machines that share OUTPUT (a cluster's job array): with
/// --shard I/N, parts I, I + N, ... of the labs' parts in order are measured into OUTPUT/parts; with --assemble,
/// the parts missing (or measured with other options or another build's study program) are measured here, and
/// trade.csv and the plots are written from all of them, the points in the order one run prints them.
void runTradeInParts(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs,
                     const CommandLine& command) {
    const fs::path dir = fs::absolute(o.output);
    const fs::path partsDir = dir / "parts";
    fs::create_directories(partsDir);
    std::vector<Part> parts;
    for (const engine::Assignment* a : labs) {
        std::size_t k = 0;
        for (const IntegratorKind& kind : kIntegrators) {
            parts.push_back({a, kind.name, k++, partsDir / (a->id + "." + kind.name + ".json")});
        }
    }
    std::vector<std::size_t> mine;
    const auto [shard, shards] = o.shard.empty() ? std::pair<int, int>{1, 1} : command.parseShard(o.shard);
    for (std::size_t i = static_cast<std::size_t>(shard - 1); i < parts.size(); i += static_cast<std::size_t>(shards)) {
        mine.push_back(i);
    }
    measure(o, parts, mine);
    if (!o.assemble) {
        std::cout << "Wrote " << engine::printable(partsDir.string()) << "; once every shard has finished, the same "
                  << "command with --assemble instead of --shard writes trade.csv and the plots\n";
        return;
    }
    writeTrade(o, dir, assemble(o, labs, parts));
}

}  // namespace simlab::study
