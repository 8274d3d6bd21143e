// simlab package: the student bundle and each platform's package (Gradescope, PrairieLearn, GitHub Classroom);
// simlab autograde: what Gradescope's run_autograder and PrairieLearn's entry point run.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
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
    nlohmann::json j = nlohmann::json::parse(engine::readFile(file.string()), nullptr, false);
    if (j.is_discarded() || !j.is_object()) throw engine::UsageError(engine::printable(file.string()) + " is not JSON");
    return j;
}

// A date-time text of the metadata at `path` ("assignment", "due_date"), as UTC seconds; empty where absent.
std::optional<std::time_t> metadataTime(const nlohmann::json& j, const std::vector<std::string>& path) {
    const nlohmann::json* at = &j;
    for (const std::string& key : path) {
        if (at->is_array() && key.size() == 1 && std::isdigit(static_cast<unsigned char>(key[0]))) {
            const std::size_t index = static_cast<std::size_t>(key[0] - '0');
            if (index >= at->size()) return std::nullopt;
            at = &(*at)[index];
        } else if (at->is_object() && at->contains(key)) {
            at = &(*at)[key];
        } else {
            return std::nullopt;
        }
    }
    return at->is_string() ? engine::parseTime(at->get<std::string>()) : std::nullopt;
}

// The course's late policy (--course, else course.toml beside the rubric) applied to the record from Gradescope's
// metadata: created_at is when it was handed in; the due date is course.toml's for the assignment, else the
// student's own in the metadata (an extension given in Gradescope included), else the assignment's, with its late
// due date as the cutoff.
void applyAutogradeLate(const AutogradeOptions& o, const engine::Assignment& assignment, const nlohmann::json& metadata,
                        engine::StudentRecord& r) {
    using namespace simlab::engine;
    const std::string path =
        !o.course.empty() ? o.course : (fs::path(assignment.rubric).parent_path() / "course.toml").string();
    if (!o.course.empty() && !fs::is_regular_file(path)) throw UsageError("no course file " + printable(path));
    if (!fs::is_regular_file(path) || metadata.is_null()) return;
    LatePolicy policy = loadLatePolicy(path, assignment.id, {});
    if (!policy.active) {
        const std::optional<std::time_t> own = metadataTime(metadata, {"users", "0", "assignment", "due_date"});
        const std::optional<std::time_t> due = own ? own : metadataTime(metadata, {"assignment", "due_date"});
        if (!due) return;
        policy.due = *due;
        policy.cutoff = metadataTime(metadata, {"assignment", "late_due_date"});
        policy.active = true;
    }
    if (const std::optional<std::time_t> at = metadataTime(metadata, {"created_at"})) {
        r.submitted = utcText(*at);
        r.submittedFrom = "Gradescope's created_at";
    }
    applyLatePolicy(r, policy);
}

// The student Gradescope's metadata names (users[0]'s sid, else their email): empty where it names nobody.
std::string studentOfMetadata(const nlohmann::json& j) {
    if (j.is_null()) return "";
    const nlohmann::json users = j.value("users", nlohmann::json::array());
    if (!users.is_array() || users.empty() || !users[0].is_object()) return "";
    for (const char* key : {"sid", "email"}) {
        const nlohmann::json& value = users[0].value(key, nlohmann::json());
        if (value.is_string() && !value.get<std::string>().empty()) return value.get<std::string>();
        if (value.is_number_integer()) return value.dump();
    }
    return "";
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
        const GradeReport report =
            gradeFolder(Builder(manifest), assignment, rubric, o.submission, /*recursive=*/true, /*followFolder=*/true,
                        options);
        if (o.format == "prairielearn") {
            writeFileAtomically(o.results, prairieLearnJson(report));
        } else {
            StudentRecord record = recordOf(report);
            record.id = options.student;
            applyAutogradeLate(o, assignment, metadata, record);
            writeFileAtomically(o.results, resultsJson(record));
            if (!record.late.line.empty()) std::cout << "Lateness: " << printable(record.late.line) << "\n";
        }
        std::cout << renderText(report);
    } catch (const std::exception& e) {
        if (o.format == "prairielearn") {
            writeFileAtomically(o.results, prairieLearnErrorJson(e.what()));
            throw;
        }
        const nlohmann::json failed = {
            {"score", 0},
            {"output", std::string("The autograder could not grade this submission: ") + printable(e.what())},
            {"tests", nlohmann::json::array()}};
        writeFileAtomically(o.results, failed.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
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
