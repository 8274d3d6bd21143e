// simlab package: the student bundle and each platform's package (Gradescope, PrairieLearn, GitHub Classroom);
// simlab autograde: what Gradescope's run_autograder and PrairieLearn's entry point run.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "commands.h"
#include "simlab/course/batch.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/course/metadata.h"
#include "simlab/course/package.h"
#include "simlab/course/policy.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;

namespace simlab::cli {

namespace {

struct PackageOptions {
    std::string assignment;
    std::string output;
    engine::PrairieLearnOptions prairieLearn;
};

void printSummary(const engine::PackageSummary& s, const std::string& where) {
    std::cout << "Wrote " << where << ": " << s.files << " files.\n";
    for (const std::string& line : s.left) std::cout << "  left out: " << line << "\n";
    for (const std::string& line : s.made) std::cout << "  made: " << line << "\n";
}

struct AutogradeOptions {
    std::string assignment;
    std::string submission;
    std::string results;
    std::string format = "gradescope";
    std::string judge;
    std::string student;
    std::string metadata;
    std::string course;
};

// Gradescope's submission_metadata.json (--metadata, else beside the submission folder); null where there is none.
// A file that is there but unreadable is an error.
nlohmann::json metadataOf(const AutogradeOptions& o) {
    const fs::path file =
        !o.metadata.empty() ? fs::path(o.metadata)
                            : fs::absolute(o.submission).lexically_normal().parent_path() / "submission_metadata.json";
    if (o.metadata.empty() && !fs::exists(file)) return nullptr;
    return engine::readSubmissionMetadata(engine::readFile(file.string()), file.string());
}

// The course's rules (--course, else course.toml beside the rubric, if there is one): its late policy, its cap on
// graded submissions, its bank of slip days. None without a file.
std::optional<engine::LatePolicy> courseRules(const AutogradeOptions& o, const engine::Assignment& assignment) {
    using namespace simlab::engine;
    const std::string path =
        !o.course.empty() ? o.course : (fs::path(assignment.rubric).parent_path() / "course.toml").string();
    if (!o.course.empty() && !fs::is_regular_file(path)) throw UsageError("no course file " + printable(path));
    if (!fs::is_regular_file(path)) return std::nullopt;
    return loadLatePolicy(path, assignment.id, {});
}

// The course's late policy applied to the record from Gradescope's metadata: created_at is when it was handed in;
// the due date is course.toml's for the assignment, else the student's own in the metadata (an extension given in
// Gradescope included), else the assignment's, with its late due date as the cutoff. A bank of slip days is the
// labs' together, which one submission does not show: the lateness is said, and left to simlab grade.
void applyAutogradeLate(engine::LatePolicy policy, const nlohmann::json& metadata, engine::StudentRecord& r) {
    using namespace simlab::engine;
    if (metadata.is_null()) return;
    policy = metadataLatePolicy(policy, metadata);
    if (!policy.active) return;
    if (const std::optional<std::time_t> at = metadataTime(metadata, {"created_at"})) {
        r.submitted = utcText(*at);
        r.submittedFrom = "Gradescope's created_at";
    }
    applyLatePolicy(r, policy);
}

// Where this submission stands against the course's cap, from Gradescope's metadata: its created_at, and
// previous_submissions, each with its submission_time, score and results. A submission past the cap keeps the
// results of the last counted one (`kept`). One the metadata gives nothing to check against is graded and counted,
// and says so: a platform's missing record never costs a student a grade.
struct CapCheck {
    engine::SubmissionsNote note;
    std::optional<nlohmann::json> kept;
    double keptScore = 0;
};

CapCheck checkCap(const engine::SubmissionCap& cap, const nlohmann::json& metadata) {
    using namespace simlab::engine;
    CapCheck check;
    check.note.max = cap.max;
    check.note.windowHours = cap.windowHours;
    const std::string counts = std::to_string(cap.max) + " graded submission" + (cap.max == 1 ? "" : "s") +
                               (cap.windowHours > 0 ? " each " + points(cap.windowHours) + " h" : "");
    auto unchecked = [&](const std::string& why) {
        check.note.checked = false;
        check.note.line = "the course counts " + counts + ", but this one cannot be checked against them: " + why +
                          "; graded, and counted";
        return check;
    };
    if (metadata.is_null()) return unchecked("there is no submission_metadata.json");
    const std::optional<std::time_t> at = metadataTime(metadata, {"created_at"});
    if (!at) return unchecked("submission_metadata.json has no created_at");
    if (!metadata.contains("previous_submissions"))
        return unchecked("submission_metadata.json has no previous_submissions");
    const nlohmann::json& previous = metadata["previous_submissions"];
    if (!previous.is_array()) return unchecked("previous_submissions in submission_metadata.json is not a list");
    std::vector<PriorSubmission> prior;
    for (std::size_t i = 0; i < previous.size(); ++i) {
        const nlohmann::json& p = previous[i];
        const std::string which = "previous_submissions[" + std::to_string(i) + "]";
        const std::optional<std::time_t> time = metadataTime(p, {"submission_time"});
        if (!time) return unchecked(which + " has no submission_time");
        PriorSubmission s;
        s.at = *time;
        const nlohmann::json score = p.is_object() ? p.value("score", nlohmann::json()) : nlohmann::json();
        if (score.is_number()) s.score = score.get<double>();
        if (score.is_string()) {
            const std::string text = score.get<std::string>();
            char* end = nullptr;
            const double value = std::strtod(text.c_str(), &end);
            if (!text.empty() && *end == '\0' && std::isfinite(value)) s.score = value;
        }
        // One the autograder could not grade (its results say so) is no graded submission of the student's.
        const nlohmann::json results = p.is_object() ? p.value("results", nlohmann::json()) : nlohmann::json();
        s.graded = !(results.is_object() && results.contains("extra_data") && results["extra_data"].is_object() &&
                     results["extra_data"].value("graded", true) == false);
        prior.push_back(s);
    }
    const CapStanding standing = capStanding(cap, *at, prior);
    if (!standing.counted && !prior[*standing.kept].score) {
        return unchecked("the submission of " + utcText(prior[*standing.kept].at) +
                         ", whose score it would keep, has none in submission_metadata.json");
    }
    check.note.line = standing.line;
    check.note.counted = standing.counted;
    check.note.number = standing.number;
    check.note.left = standing.left;
    if (!standing.counted) {
        check.kept = previous[*standing.kept].value("results", nlohmann::json());
        check.keptScore = *prior[*standing.kept].score;
    }
    return check;
}

// The platform needs a results.json whatever happens: an error becomes one, with the reason in it.
void runAutograde(const AutogradeOptions& o) {
    using namespace simlab::engine;
    fs::create_directories(fs::absolute(o.results).parent_path());
    try {
        const Manifest manifest = loadManifest();
        sayLeftovers(sweepLeftovers());
        Assignment assignment = manifest.find(o.assignment);
        if (!o.judge.empty()) {
            // A judge made apart, with the hidden tests (PrairieLearn's tests/judge): no sandbox sees it.
            if (!fs::is_regular_file(o.judge)) throw UsageError("no judge at " + o.judge);
            assignment.judge = fs::absolute(o.judge).lexically_normal().string();
            assignment.hiddenTestsBuilt = true;
            // Its folder (the question's tests/, which holds the hidden tests' sources too) is simlab's place.
            isolation::addPlaces({fs::path(assignment.judge).parent_path().string()});
        }
        if (!fs::is_directory(o.submission)) throw UsageError("no submission folder " + o.submission);
        const Rubric rubric = loadRubric(assignment.rubric);
        if (const std::string closed = sandboxCannotReach(manifest, assignment); !closed.empty()) throw UsageError(closed);
        if (const std::string exposed = placesExposed(manifest); !exposed.empty()) throw UsageError(exposed);
        GradeOptions options;
        options.includeHidden = true;
        options.judges = cores();  // one submission
        const nlohmann::json metadata = metadataOf(o);
        options.student = o.student.empty() ? studentOfMetadata(metadata) : o.student;
        requireStudentId(options.student);
        // PrairieLearn keeps its own dates and rate of grading; on Gradescope, the course's rules.
        const std::optional<LatePolicy> course = o.format == "prairielearn" ? std::nullopt : courseRules(o, assignment);
        const bool capped = course && course->cap.max > 0;
        CapCheck cap;
        if (capped) {
            // Past the cap, nothing runs: the score stays the last counted one's, and says why.
            cap = checkCap(course->cap, metadata);
            if (cap.kept) {
                writeFileAtomically(o.results, keptResultsJson(*cap.kept, cap.keptScore, cap.note));
                std::cout << "Submissions: " << printable(cap.note.line) << "\n";
                return;
            }
        }
        const GradeReport report =
            gradeFolder(Builder(manifest), assignment, rubric, o.submission, /*recursive=*/true, /*followFolder=*/true,
                        options);
        if (o.format == "prairielearn") {
            writeFileAtomically(o.results, prairieLearnJson(report));
        } else {
            StudentRecord record = recordOf(report);
            record.id = options.student;
            if (course) applyAutogradeLate(*course, metadata, record);
            writeFileAtomically(o.results, capped ? resultsJson(record, cap.note) : resultsJson(record));
            if (!record.late.line.empty()) std::cout << "Lateness: " << printable(record.late.line) << "\n";
            if (capped) std::cout << "Submissions: " << printable(cap.note.line) << "\n";
        }
        std::cout << renderText(report);
    } catch (const std::exception& e) {
        if (o.format == "prairielearn") {
            writeFileAtomically(o.results, prairieLearnErrorJson(e.what()));
            throw;
        }
        writeFileAtomically(o.results, resultsErrorJson(e.what()));
        throw;
    }
}

using PackageWriter =
    std::function<engine::PackageSummary(const engine::Manifest&, const engine::Assignment&, const PackageOptions&)>;

// The manifest of a build tree or of an installation: packages are made from the project's sources, which an
// installation made before it carried them all has only the graded part of.
engine::Manifest sourceTreeManifest() {
    engine::Manifest manifest = engine::loadManifest();
    if (manifest.installed && !fs::exists(manifest.sourceDir + "/scripts/setup")) {
        throw engine::UsageError("simlab package makes its packages from the project's source tree, and this simlab is "
                                 "installed (" + engine::printable(manifest.prefix) + "): run the simlab of a build of "
                                 "the project (build/bin/simlab)");
    }
    return manifest;
}

// A `package` subcommand that writes one assignment's package to --output with `write`.
CLI::App* addAssignmentPackage(CLI::App* package, const std::string& name, const std::string& help,
                               const std::string& output, const std::shared_ptr<PackageOptions>& options,
                               const PackageWriter& write) {
    CLI::App* sub = package->add_subcommand(name, help);
    sub->add_option("assignment", options->assignment, "which assignment")->required();
    sub->add_option("-o,--output", options->output, output)->required();
    sub->callback([options, write] {
        const engine::Manifest manifest = sourceTreeManifest();
        printSummary(write(manifest, manifest.find(options->assignment), *options), options->output);
    });
    return sub;
}

}  // namespace

void addPackage(CLI::App& app) {
    CLI::App* package = app.add_subcommand(
        "package",
        "Make what you hand out: the student bundle, or an assignment's autograder for Gradescope, "
        "PrairieLearn or GitHub Classroom. Gradescope and PrairieLearn grade each submission on their "
        "servers, hidden tests included; Classroom's template only self-checks each push, and you grade "
        "the cloned repositories with simlab grade --from classroom.");
    package->require_subcommand(1);

    auto student = std::make_shared<PackageOptions>();
    CLI::App* s = package->add_subcommand(
        "student", "Write the student bundle: everything but the solutions, the hidden tests and the corpus. It "
                   "builds with scripts/setup and self-checks with simlab check.");
    s->add_option("lab", student->assignment,
                  "a lab of one's own (its folder) the bundle carries too, as labs/<its folder's name>");
    s->add_option("-o,--output", student->output, "a new folder for the bundle")->required();
    s->callback([student] {
        const engine::Manifest manifest = sourceTreeManifest();
        const engine::Assignment* lab = nullptr;
        if (!student->assignment.empty()) {
            lab = &manifest.find(student->assignment);
            if (!engine::isOwnLab(manifest, *lab)) {
                throw engine::UsageError(student->assignment + " is one of the course's labs, which every bundle "
                                         "carries: name a lab of one's own (its folder), or none");
            }
        }
        printSummary(engine::writeStudentBundle(manifest, student->output, lab), student->output);
    });

    // What `cmake --install` runs (the project's CMakeLists.txt): not listed, since nobody types it.
    auto tree = std::make_shared<PackageOptions>();
    CLI::App* t = package->add_subcommand(
        "installed-tree", "Write this build's installed files below DIR (DESTDIR and the prefix): the build's "
                          "part in lib/simlab, the sources' in share/simlab; cmake --install runs this.");
    t->group("");
    t->add_option("dir", tree->output, "the prefix, with DESTDIR before it")->required();
    t->callback([tree] {
        const engine::Manifest manifest = sourceTreeManifest();
        printSummary(engine::writeInstalledTree(manifest, tree->output), tree->output);
    });

    addAssignmentPackage(
        package, "gradescope",
        "Write a Gradescope autograder archive for one assignment: setup.sh builds simlab on Gradescope's image "
        "(choose Ubuntu 24.04), run_autograder grades each submission on every test, hidden tests marked by their "
        "rubric visibility.",
        "the zip file to write", std::make_shared<PackageOptions>(),
        [](const engine::Manifest& m, const engine::Assignment& a, const PackageOptions& o) {
            return engine::writeGradescopeZip(m, a, o.output);
        });

    auto prairieLearn = std::make_shared<PackageOptions>();
    CLI::App* p = addAssignmentPackage(
        package, "prairielearn",
        "Write a PrairieLearn question folder for one assignment, graded externally on every test: info.json, "
        "question.html, the starter file, tests/run_autograder (the entry point: grades /grade/student into "
        "/grade/results/results.json), and image/, the grading image's Dockerfile and sources (build and push it "
        "under the --image name).",
        "a new folder: the question (copy it into questions/)", prairieLearn,
        [](const engine::Manifest& m, const engine::Assignment& a, const PackageOptions& o) {
            return engine::writePrairieLearnQuestion(m, a, o.output, o.prairieLearn);
        });
    p->add_option("--image", prairieLearn->prairieLearn.image,
                  "the grading image's name, as PrairieLearn pulls it (default: simlab-grader)");
    p->add_option("--timeout", prairieLearn->prairieLearn.timeout,
                  "seconds a grading job may take, 1 to 600 (default: 300)")
        ->check(CLI::Range(1, 600));
    p->add_flag("--upload", prairieLearn->prairieLearn.upload,
                "students upload their file (pl-file-upload) instead of editing it in the page");

    CLI::App* classroom = addAssignmentPackage(
        package, "github-classroom",
        "Write the template repository of a GitHub Classroom assignment: the student bundle and a workflow that, on "
        "every push, builds simlab, runs the visible tests and reports their points to Classroom. Those points are "
        "a self-check (the student's repository can change them); grade the cloned repositories with simlab grade.",
        "a new folder: the template repository", std::make_shared<PackageOptions>(),
        [](const engine::Manifest& m, const engine::Assignment& a, const PackageOptions& o) {
            return engine::writeClassroomTemplate(m, a, o.output);
        });
    classroom->alias("classroom");  // as simlab grade --from names the platform
}

void addAutograde(CLI::App& app) {
    auto options = std::make_shared<AutogradeOptions>();
    CLI::App* a = app.add_subcommand(
        "autograde", "Grade one submission folder on every test and write the platform's results.json (what "
                     "Gradescope's run_autograder and PrairieLearn's entry point run). The file is searched for in "
                     "subfolders too; a lone C++ file of another name is graded and noted. A results.json is "
                     "written whatever happens.");
    a->add_option("assignment", options->assignment, "which assignment")->required();
    a->add_option("--submission", options->submission, "the submission folder")->required();
    a->add_option("--results", options->results, "where to write results.json")->required();
    a->add_option("--format", options->format, "gradescope, or prairielearn")
        ->check(CLI::IsMember({"gradescope", "prairielearn"}))
        ->capture_default_str();
    a->add_option("--judge", options->judge,
                  "the assignment's judge, with its hidden tests, made apart from this simlab (a PrairieLearn "
                  "question's tests/judge: scripts/prairielearn-judge)");
    a->add_option("--student", options->student,
                  "the student's id, for a rubric that gives each student their own trade scene ([variants]); "
                  "default: users[0]'s sid, else email, of --metadata");
    a->add_option("--metadata", options->metadata,
                  "Gradescope's submission_metadata.json (default: the one beside the submission folder, if any)");
    a->add_option("--course", options->course,
                  "the course's rules for late work (default: course.toml beside the rubric, if there is one), "
                  "applied from Gradescope's created_at; the due date is course.toml's, else the metadata's")
        ->check(CLI::ExistingFile);
    a->callback([options] { runAutograde(*options); });
}

}  // namespace simlab::cli
