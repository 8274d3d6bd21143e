// `simlab study trade` and `simlab study minimal`: which labs and programs a study runs, the trade question's
// scene and its sweeps, the fronts of the question's data files, and each lab's study program at once.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "internal.h"
#include "simlab/build/build.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/common/text.h"
#include "simlab/isolation/process.h"
#include "simlab/trade_question.h"
#include "simlab/work_precision.h"

namespace simlab::study {

namespace {

/// A lab's trade question as its data file states it: `kind` is "question" (grading/trade-question.json) or
/// "hidden" (grading/trade-hidden.json, absent from the student bundle).
simlab::trade::Question tradeQuestionOf(const engine::Assignment& a, const std::string& kind) {
    const fs::path file = fs::path(a.dir) / "grading" / ("trade-" + kind + ".json");
    if (!fs::exists(file)) throw engine::UsageError(a.id + " has no trade question (" + file.string() + ")");
    try {
        return simlab::trade::parseQuestion(engine::readFile(file.string()), file.string());
    } catch (const std::runtime_error& e) {
        throw engine::UsageError(e.what());
    }
}

/// The scene of `q` a --question study measures: the student's own (--student) where the rubric gives each one.
const simlab::trade::Scene& studiedScene(const StudyOptions& o, const engine::Assignment& a,
                                         const simlab::trade::Question& q) {
    const Variants v = loadRubric(a.rubric).variants;
    return simlab::trade::sceneFor(q, v.perStudent, v.seed, o.student);
}

/// The study program's arguments for scene `s` of `q`: the scene, its final time, the starts and what they move,
/// and the integrators the question allows.
std::vector<std::string> sceneArguments(const simlab::trade::Question& q, const simlab::trade::Scene& s) {
    char finalTime[32];
    std::snprintf(finalTime, sizeof finalTime, "%.17g", s.finalTime);
    // The study's subject is a plain word: "projectile-a-faster-flatter-throw-33-m-s-at-50-degrees".
    std::string subject = q.lab + "-";
    for (const char c : s.name) {
        const bool plain = std::isalnum(static_cast<unsigned char>(c)) != 0;
        if (plain || subject.back() != '-') subject += plain ? c : '-';
    }
    while (subject.size() > 64 || subject.back() == '-') subject.pop_back();
    std::vector<std::string> argv = {"--scene", s.scene.dump(), "--final-time", finalTime,
                                     "--name",  subject,        "--starts",     std::to_string(q.starts)};
    if (!q.nudge.empty()) argv.insert(argv.end(), {"--nudge", q.nudge});
    if (!q.integrators.empty()) {
        std::string names;
        for (const std::string& name : q.integrators) names += (names.empty() ? "" : ",") + name;
        argv.insert(argv.end(), {"--integrators", names});
    }
    if (q.fixedStepOnly) argv.push_back("--fixed-steps-only");
    return argv;
}

/// The most evaluations an answer to `q` may take on its scene, where the grader stops its run and gives it nothing
/// (trade::cap, with the rubric's beyond and none_past of the visible trade test) on scene `s`; 0 where the tree
/// does not say.
double questionCap(const engine::Assignment& a, const simlab::trade::Question& q, const simlab::trade::Scene& s,
                   double* beyond, double* nonePast) {
    const Rubric rubric = loadRubric(a.rubric);
    for (const RubricTest& t : rubric.tests) {
        if (!t.visible() || !t.params.count("beyond") || !t.params.count("none_past")) continue;
        *beyond = t.params.at("beyond");
        *nonePast = t.params.at("none_past");
        const std::vector<work_precision::Point>& front = s.front;
        return front.empty() ? 0 : simlab::trade::cap(front, q.digits, *beyond, *nonePast);
    }
    return 0;
}

/// The most sweeps a study program may say its study has.
constexpr std::size_t kMostSweeps = 1000;

/// A study in its sweeps (the study program's --sweep: an integrator's accuracies or its fixed steps, for each of its
/// scenes), one run of `argv` per sweep, `jobs` runs at once, with a progress line every few seconds. Each run names
/// every scene first; the first run's lines say how many sweeps and points each scene has, and the scenes come in
/// its order, each scene's points in the order one run prints them.
std::vector<SubjectRun> runSweeps(const std::vector<std::string>& argv, bool sandboxed, const std::string& lab,
                                  int jobs) {
    std::mutex lock;
    std::condition_variable counted;
    std::vector<json> subjects;  // the first run's scenes
    std::size_t sweeps = 0, total = 0;
    bool firstEnded = false;
    std::string odd;                                            // what a run printed that no study does
    std::vector<std::map<std::string, std::vector<json>>> points;  // each sweep's points, by scene
    std::vector<int> statuses;
    Progress progress;
    forEachInParallel(kMostSweeps, jobs, [&](std::size_t k) {
        // The other runs wait for the first's subject line, or for its end, whatever ends it; none runs past the
        // sweeps it says there are.
        if (k > 0) {
            std::unique_lock<std::mutex> guard(lock);
            counted.wait(guard, [&] { return sweeps > 0 || firstEnded; });
            if (k >= sweeps) return;
        }
        std::vector<std::string> args = argv;
        args.insert(args.end(), {"--sweep", std::to_string(k)});
        std::map<std::string, std::vector<json>> mine;
        struct Ended {
            std::function<void()> tell;
            ~Ended() { tell(); }
        } ended{[&, k] {
            if (k != 0) return;
            std::lock_guard<std::mutex> guard(lock);
            firstEnded = true;
            counted.notify_all();
        }};
        const int status = runStudyProgram(args, sandboxed, [&](const json& j) {
            if (text(j["type"]) == "point") {
                mine[text(j["subject"])].push_back(j);
                progress.pointDone();
                return;
            }
            if (text(j["type"]) != "subject" || k != 0) return;
            // What a student's program says is data: counts out of reason stop the study below.
            const double n = j["sweeps"].is_number() ? j["sweeps"].get<double>() : 0;
            const double count = j["points"].is_number() ? j["points"].get<double>() : 0;
            std::lock_guard<std::mutex> guard(lock);
            const bool named = std::any_of(subjects.begin(), subjects.end(),
                                           [&](const json& s) { return s["subject"] == j["subject"]; });
            if (named || !(n >= 1 && n <= static_cast<double>(kMostSweeps) && count >= n && count <= 100000) ||
                (sweeps > 0 && n != static_cast<double>(sweeps)) || subjects.size() >= 100) {
                if (odd.empty()) odd = "a scene's subject line out of reason (" + text(j["subject"]) + ")";
                return;
            }
            subjects.push_back(j);
            total += static_cast<std::size_t>(count);
            progress.setTotal(total);
            if (sweeps == 0) {
                sweeps = static_cast<std::size_t>(n);
                points.resize(sweeps);
                statuses.assign(sweeps, 0);
                counted.notify_all();
            }
        });
        std::lock_guard<std::mutex> guard(lock);
        if (sweeps == 0) {
            statuses.assign(1, status);
            return;
        }
        points[k] = std::move(mine);
        statuses[k] = status;
    });
    for (const int status : statuses) {
        if (status != 0) {
            throw std::runtime_error("the study of " + lab + " stopped with status " + std::to_string(status));
        }
    }
    const std::string program = fs::path(argv.front()).filename().string();
    if (subjects.empty()) throw std::runtime_error(program + " did not say how many points and sweeps its study has");
    if (!odd.empty()) throw std::runtime_error(program + " printed " + odd + ": the study stops");
    std::vector<SubjectRun> runs;
    for (const json& subject : subjects) {
        SubjectRun run{subject, {}, {}};
        for (std::map<std::string, std::vector<json>>& sweep : points) {
            std::vector<json>& mine = sweep[text(subject["subject"])];
            run.points.insert(run.points.end(), mine.begin(), mine.end());
        }
        runs.push_back(std::move(run));
    }
    for (std::map<std::string, std::vector<json>>& sweep : points) {
        for (const auto& entry : sweep) {
            const std::string& name = entry.first;
            if (!entry.second.empty() && std::none_of(subjects.begin(), subjects.end(),
                                                      [&](const json& s) { return text(s["subject"]) == name; })) {
                throw std::runtime_error(program + " printed a point of a scene it did not name (" + name +
                                         "): the study stops");
            }
        }
    }
    progress.finish(true);
    return runs;
}

/// `simlab study trade LAB --fronts`: every scene of the lab's trade question (and of its hidden variants, where the
/// tree has them) studied on the reference solution as the grader measures an answer, and each scene's front -
/// the points no cheaper point matches in digits - written into its data file.
void writeFronts(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs) {
    struct Task {
        const engine::Assignment* lab;
        fs::path file;
        json data;
        std::string list;  ///< "scenes", or "variants": the pool of students' own scenes
        std::size_t scene;
        std::vector<work_precision::Point> points;
        int status = 0;
    };
    std::vector<Task> tasks;
    for (const engine::Assignment* a : labs) {
        for (const std::string kind : {"question", "hidden"}) {
            const fs::path file = fs::path(a->dir) / "grading" / ("trade-" + kind + ".json");
            if (!fs::exists(file)) continue;
            const json data = json::parse(engine::readFile(file.string()));
            for (const std::string list : {"scenes", "variants"}) {
                if (!data.contains(list)) continue;
                for (std::size_t i = 0; i < data[list].size(); ++i) tasks.push_back({a, file, data, list, i, {}, 0});
            }
        }
    }
    if (tasks.empty()) throw engine::UsageError("no trade question here to make fronts for");
    std::mutex told;
    forEachInParallel(tasks.size(), std::min<int>(o.jobs, static_cast<int>(tasks.size())), [&](std::size_t i) {
        Task& t = tasks[i];
        const simlab::trade::Question q = simlab::trade::parseQuestion(t.data.dump(), t.file.string());
        const simlab::trade::Scene& studied = (t.list == "scenes" ? q.scenes : q.variants).at(t.scene);
        std::vector<std::string> argv = {t.lab->studyProgramPath};
        const std::vector<std::string> scene = sceneArguments(q, studied);
        argv.insert(argv.end(), scene.begin(), scene.end());
        argv.insert(argv.end(), {"--repeats", "1"});
        if (o.quick) argv.push_back("--quick");
        if (o.maxEvaluations > 0) argv.insert(argv.end(), {"--max-evaluations", std::to_string(o.maxEvaluations)});
        if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
        {
            std::lock_guard<std::mutex> guard(told);
            std::cerr << "fronts: " << t.lab->id << ", " << studied.name << " (" << t.file.filename().string() << ")\n";
        }
        t.status = runStudyProgram(argv, false, [&t](const json& j) {
            if (text(j["type"]) != "point" || text(j["status"]) != "ok") return;
            if (!j["worst_digits"].is_number() || !j["evaluations"].is_number()) return;
            t.points.push_back({j["worst_digits"].get<double>(), j["evaluations"].get<double>(), 0});
        });
    });
    // Each file once, with every scene's front in it.
    std::map<std::string, json> written;
    for (Task& t : tasks) {
        if (t.status != 0) {
            throw std::runtime_error("the study of " + t.lab->id + " stopped with status " + std::to_string(t.status));
        }
        json& data = written.count(t.file.string()) ? written[t.file.string()] : (written[t.file.string()] = t.data);
        json& scene = data[t.list][t.scene];
        const std::vector<work_precision::Point> front = work_precision::frontOf(t.points);
        const double digits = data.at("digits").get<double>();
        if (front.empty() || front.back().digits < digits) {
            throw engine::UsageError(t.lab->id + ": no setting keeps " + number(data["digits"], "%g") + " digits on '" +
                                     text(scene["name"]) + "' under the cap: the question cannot be answered there");
        }
        scene["front"] = json::array();
        for (const work_precision::Point& p : front) {
            char d[32];
            std::snprintf(d, sizeof d, "%.4f", p.digits);
            scene["front"].push_back({std::stod(d), p.cost});
        }
        std::cout << t.lab->id << ", " << text(scene["name"]) << ": " << front.size() << " points on the front; "
                  << number(data["digits"], "%g") << " digits cost "
                  << number(json(work_precision::costAt(front, digits)->cost), "%.0f") << " evaluations\n";
    }
    for (const auto& [file, data] : written) {
        engine::writeFileAtomically(file, data.dump(2) + "\n");
        std::cout << "Written: " << engine::printable(file) << '\n';
    }
}

/// The labs `o` names that have a study (of the reference solution, or with --file of a student's file).
std::vector<const engine::Assignment*> studiedLabs(const engine::Manifest& manifest, const StudyOptions& o) {
    std::vector<const engine::Assignment*> labs;
    if (o.lab == "all") {
        for (const engine::Assignment& a : manifest.assignments) {
            if (!a.studyProgramPath.empty()) labs.push_back(&a);
        }
    } else {
        const engine::Assignment& a = manifest.find(o.lab);
        if (a.studyProgramPath.empty() && (o.file.empty() || a.studyObjects.empty())) {
            throw engine::UsageError("no study of " + o.lab +
                                     "'s reference solution, which is not in this tree: study your own file with "
                                     "--file (e.g. --file " + engine::printable(a.starter) + ")");
        }
        labs.push_back(&a);
    }
    if (labs.empty())
        throw engine::UsageError("no lab here has a study (their reference solutions are not in this tree)");
    return labs;
}

/// What the trade question asks, and where its study stops each point, told before the study begins.
void describeQuestion(const StudyOptions& o, const engine::Assignment& a) {
    const simlab::trade::Question q = tradeQuestionOf(a, "question");
    const simlab::trade::Scene& studied = studiedScene(o, a, q);
    std::cout << "The trade question of " << q.lab << ": " << q.digits << " digits at every step to "
              << studied.finalTime << " s of " << (studied.name == "question" ? "this scene" : "'" + studied.name + "'")
              << " (the rest as the lab's default one)";
    if (!q.integrators.empty() || q.fixedStepOnly) {
        std::string names;
        for (const std::string& name : q.integrators) names += (names.empty() ? "" : ", ") + name;
        std::cout << ", with " << (names.empty() ? "any integrator" : names)
                  << (q.fixedStepOnly ? " at fixed steps" : "");
    }
    std::cout << ":\n  " << studied.scene.dump() << "\n";
    if (q.starts > 1) {
        // "/w_B0/0" reads w_B0[0].
        std::string moved;
        for (std::size_t at = 1, next; at <= q.nudge.size(); at = next + 1) {
            next = std::min(q.nudge.find('/', at), q.nudge.size());
            const std::string part = q.nudge.substr(at, next - at);
            const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
            moved += index ? "[" + part + "]" : moved.empty() ? part : "." + part;
        }
        std::cout << "Each point is measured from " << q.starts << " starts (" << moved
                  << " moved in its last digit) and kept at its worst, as the grader measures an answer; one short "
                  << "of " << q.digits << " digits from the first is no answer, measured from that start alone.\n";
    }
    double beyond = 0, nonePast = 0;
    const double cap = questionCap(a, q, studied, &beyond, &nonePast);
    const std::string why = number(json(nonePast), "%g") + " times the front's cost at " +
                            number(json(q.digits + beyond), "%g") + " digits";
    if (cap > 0 && o.maxEvaluations > 0 && o.maxEvaluations < cap) {
        std::cout << "Each point is stopped past " << number(json(o.maxEvaluations), "%.0f")
                  << " evaluations (--max-evaluations), short of where the grader stops an answer: "
                  << number(json(cap), "%.0f") << ", " << why << ".\n";
    } else if (cap > 0) {
        std::cout << "Each point is stopped past " << number(json(cap), "%.0f") << " evaluations, where the grader "
                  << "stops an answer: " << why << ", past which it earns nothing.\n";
    }
}

/// The labs whose study is of a student's own file: those with a study that no project makes its own.
std::vector<std::string> studiedFiles(const engine::Manifest& manifest) {
    return manifest.ids([](const engine::Assignment& a) { return !a.projects && !a.studyObjects.empty(); });
}

/// A student's file built into a study program of its own (buildStudyOfFile), for `study trade` and `study
/// minimal`: one lab's file, of a lab whose study is of the student's model (not a projects lab's, whose study is
/// its worked example's); empty
/// for a study of the reference solution.
StudyProgram studyProgramOf(const StudyOptions& o, const engine::Manifest& manifest,
                            const std::vector<const engine::Assignment*>& labs, const CommandLine& command) {
    if (o.file.empty()) return {};
    if (o.lab == "all" || labs.front()->projects) {
        throw engine::UsageError("--file studies one lab's file: " + engine::spokenList(studiedFiles(manifest)) +
                                 (o.lab == "all" ? "" : " (" + o.lab + "'s study is its worked example's)"));
    }
    return buildStudyOfFile(manifest, *labs.front(), o.file, command);
}

/// The question's study, into `dir`: its sweeps on every core, each point under the grader's cap on an answer and
/// measured from the grader's starts where it could be one.
void studyQuestion(const StudyOptions& o, const engine::Assignment& a, const std::string& studentProgram,
                   const fs::path& dir, int cores) {
    const simlab::trade::Question q = tradeQuestionOf(a, "question");
    std::vector<std::string> argv = {studentProgram.empty() ? a.studyProgramPath : studentProgram};
    const simlab::trade::Scene& studied = studiedScene(o, a, q);
    const std::vector<std::string> scene = sceneArguments(q, studied);
    argv.insert(argv.end(), scene.begin(), scene.end());
    char value[32];
    std::snprintf(value, sizeof value, "%.17g", q.digits);
    argv.insert(argv.end(), {"--answer-digits", value});
    if (o.quick) argv.push_back("--quick");
    if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
    double beyond = 0, nonePast = 0;
    const double cap = questionCap(a, q, studied, &beyond, &nonePast);
    const double evaluations = cap > 0 && o.maxEvaluations > 0 ? std::min(cap, o.maxEvaluations)
                               : cap > 0                       ? cap
                                                               : o.maxEvaluations;
    if (evaluations > 0) {
        std::snprintf(value, sizeof value, "%.17g", evaluations);
        argv.insert(argv.end(), {"--max-evaluations", value});
    }
    if (o.repeats > 0) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
    std::cout << std::flush;  // the question's lines before the progress lines on a shared terminal or log
    // The table's rows: the digits asked, and each whole digit past them that the grader reads the front at.
    std::vector<double> targets;
    for (int past = 0; past <= static_cast<int>(std::floor(beyond + 1e-9)); ++past) targets.push_back(q.digits + past);
    writeTrade(o, dir, runSweeps(argv, !studentProgram.empty(), a.id, cores), targets);
}

/// The labs' studies into `dir`: each lab's sweeps side by side, `jobs` runs at once, the labs one after another;
/// for `study minimal`, each lab's study program on a core of its own (`jobs` at once), each measuring its points one
/// at a time.
void studyLabs(const StudyOptions& o, const std::vector<const engine::Assignment*>& labs,
               const std::string& studentProgram, const fs::path& dir, int jobs) {
    auto argvOf = [&](const engine::Assignment* a) {
        std::vector<std::string> argv = {studentProgram.empty() ? a->studyProgramPath : studentProgram};
        if (o.minimal) argv.push_back("--minimal");
        if (o.quick) argv.push_back("--quick");
        if (o.cap > 0) argv.insert(argv.end(), {"--cap", std::to_string(o.cap)});
        if (o.maxEvaluations > 0) argv.insert(argv.end(), {"--max-evaluations", std::to_string(o.maxEvaluations)});
        if (o.repeats > 0) argv.insert(argv.end(), {"--repeats", std::to_string(o.repeats)});
        return argv;
    };
    if (!o.minimal) {
        std::vector<SubjectRun> runs;
        for (const engine::Assignment* a : labs) {
            if (labs.size() > 1) std::cerr << "  " << a->id << ":\n";
            const std::vector<SubjectRun> lab = runSweeps(argvOf(a), !studentProgram.empty(), a->id, jobs);
            runs.insert(runs.end(), lab.begin(), lab.end());
        }
        writeTrade(o, dir, runs);
        return;
    }
    std::vector<json> minimalRows;
    struct LabRun {
        std::vector<json> minimal;
        int status = 0;
    };
    std::vector<LabRun> results(labs.size());
    forEachInParallel(labs.size(), std::min<int>(jobs, static_cast<int>(labs.size())), [&](std::size_t i) {
        LabRun& r = results[i];
        r.status = runStudyProgram(argvOf(labs[i]), !studentProgram.empty(), [&r](const json& j) {
            if (text(j["type"]) == "minimal") r.minimal.push_back(j);
        });
    });
    for (std::size_t i = 0; i < labs.size(); ++i) {
        if (results[i].status != 0) {
            throw std::runtime_error("the study of " + labs[i]->id + " stopped with status " +
                                     std::to_string(results[i].status));
        }
        minimalRows.insert(minimalRows.end(), results[i].minimal.begin(), results[i].minimal.end());
    }
    writeMinimal(dir, minimalRows);
}

}  // namespace

void runTrade(const StudyOptions& o, const CommandLine& command) {
    const engine::Manifest manifest = engine::loadManifest();
    const std::vector<const engine::Assignment*> labs = studiedLabs(manifest, o);
    if ((o.question || o.fronts) && labs.front()->projects) {
        throw engine::UsageError(labs.front()->id + " has no trade question: each project's is its own");
    }
    if (o.question && o.lab == "all")
        throw engine::UsageError("--question studies one lab: " + engine::spokenList(studiedFiles(manifest)));
    if (!o.student.empty() && !o.question) throw engine::UsageError("--student goes with --question");
    if (o.fronts && !o.file.empty()) throw engine::UsageError("--fronts measures the reference solution, not --file");
    if (o.question) describeQuestion(o, *labs.front());
    if (!o.shard.empty() || o.assemble) {
        const char* clash = !o.file.empty() ? "--file" : o.question ? "--question" : o.fronts ? "--fronts" : nullptr;
        if (clash)
            throw engine::UsageError(std::string("--shard and --assemble study the reference solutions, not ") + clash);
        if (!o.shard.empty() && o.assemble)
            throw engine::UsageError("--shard measures parts, --assemble gathers them: give one");
        if (!o.shard.empty()) command.parseShard(o.shard);  // a bad I/N stops before anything is built
    }
    ensureStudiesBuilt(manifest, labs, !o.file.empty(), command.cores);
    if (!o.shard.empty() || o.assemble) {
        runTradeInParts(o, labs, command);
        return;
    }
    if (o.fronts) {
        std::vector<const engine::Assignment*> withQuestions;
        for (const engine::Assignment* a : labs) {
            if (!a->projects && !a->studyProgramPath.empty()) withQuestions.push_back(a);
        }
        writeFronts(o, withQuestions);
        return;
    }
    const StudyProgram student = studyProgramOf(o, manifest, labs, command);
    const fs::path dir = fs::absolute(o.output);
    fs::create_directories(dir);
    if (o.question) {
        studyQuestion(o, *labs.front(), student.path, dir, command.cores);
        return;
    }
    studyLabs(o, labs, student.path, dir, o.jobs);
}

}  // namespace simlab::study
