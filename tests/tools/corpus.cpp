// simlab-corpus: the corpus of sample submissions, each with the score the grader must give it.
//
// A case is a TOML file, tests/corpus/<assignment>/<case>.toml, in the format simlab/course/corpus.h describes:
// a base file (the reference solution or the starter) plus exact edits, the score and outcomes the grader must give.
//
// A case of the isolation's invariants (tests/corpus/<id>/invariants/) also says which of its code must be
// recorded, or must never run:
//
//     [invariant]
//     entry = "a local ifunc's resolver"     # the record its entry point makes
//     runs = true                            # false: it must never run (a shared object's .preinit_array)
//
//   simlab-corpus materialize <assignment> <case.toml>... --out DIR   write DIR/<case>/<files>
//   simlab-corpus check <assignment> <case.toml>                      grade the tests its edit concerns and compare
//       their outcomes; exit 1 on a mismatch (its score, and the text its report must show, are a class's to check:
//       the class grades every test)
//   simlab-corpus compare <assignment> <case.toml>... --grades DIR    compare a class graded into DIR (`simlab grade
//       --out DIR` of the materialized cases) with every case's expectations: outcomes, score, status and text
//   simlab-corpus invariants <assignment> <case.toml>...               grade each with the object check off, in the
//       sandbox this machine and environment give, and fail on any record of the witness made as root or with a
//       capability, on a walk that read a file outside what a test may read (isolation/reach.h), on an entry
//       point that did not run where it must (or ran where it must not), on a call the students' filter refuses
//       that went through (the random calls of tests/corpus/calls.inc: SIMLAB_CALLS calls at most, default 20000,
//       in SIMLAB_CALLS_MILLIS, default 1500, from SIMLAB_CALLS_SEED, default a new one each run), and on a host
//       the case changed: a file left in the shared temporary folders, a process of the test's user left, the
//       bait (a file of its own the calls aim at) or a file of simlab's places changed
//   simlab-corpus class <assignment> <case.toml>... --simlab PATH     grade them all as one class with
//       `simlab grade` (--env NAME=VALUE for it, --docker-capabilities to run it with Docker's default capabilities),
//       while listening on 127.0.0.1:47810, and compare every student; also check that no process a submission
//       started outlived the grading, that each
//       student has one gradebook row, that nobody connected to the listener, that no student's report holds
//       another student's file, a line of the hidden tests, of the rubric or of /etc/shadow, that no terminal
//       line or feedback holds a control character, that no spreadsheet cell starts a formula, that every
//       results.json is valid UTF-8 JSON, and that simlab itself stayed small; --keep DIR leaves simlab grade's
//       --out in DIR for a test that reads the same grades rather than grade again
#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <netinet/in.h>
#include <dirent.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>
#include <toml++/toml.h>

#include "simlab/course/batch.h"
#include "simlab/course/corpus.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/grading/grade.h"
#include "simlab/build/lock.h"
#include "simlab/build/manifest.h"
#include "simlab/isolation/filter.h"
#include "simlab/isolation/process.h"
#include "simlab/grading/report.h"
#include "simlab/common/text.h"

namespace fs = std::filesystem;
using namespace simlab::engine;
using namespace simlab::isolation;

namespace {

std::string gSourceDir, gBuildDir;  // this tree's, for {source_dir} and {build_dir}
std::string gWitness;               // tests/corpus/witness.inc with {reach} written in, for {witness}
std::string gCalls;                 // tests/corpus/calls.inc with its lists written in, for {calls}
std::string gBait;                  // the folder of the bait the random calls aim at

using Case = CorpusCase;

// A case with this tree's folders and the witness written into its edits and links.
Case loadCase(const Assignment& assignment, const simlab::Rubric& rubric, const std::string& path) {
    return loadCorpusCase(assignment, rubric, path,
                          {{"{source_dir}", gSourceDir}, {"{build_dir}", gBuildDir}, {"{witness}", gWitness},
                           {"{calls}", gCalls}});
}

void writeCase(const Case& c, const fs::path& dir, const std::string& classDir) { writeCorpusCase(c, dir.string(), classDir); }

std::vector<std::string> compare(const Case& c, const std::vector<TestResult>& tests, std::optional<double> score,
                                 SubmissionStatus status, const std::string& text, bool everyTest = true) {
    return compareWithCase(c, tests, score, status, text, everyTest);
}


int materialize(const Assignment& assignment, const simlab::Rubric& rubric, const std::vector<std::string>& cases,
                const std::string& out) {
    for (const std::string& path : cases) {
        const Case c = loadCase(assignment, rubric, path);
        writeCase(c, fs::path(out) / c.name, out);
    }
    return 0;
}

// Lines of a file that would betray it if they turned up in a student's report: long enough to be its own
// (25 characters, trimmed), and not the test names, which reports show by design.
std::vector<std::string> telltaleLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const std::size_t first = line.find_first_not_of(" \t"), last = line.find_last_not_of(" \t\r");
        if (first == std::string::npos) continue;
        line = line.substr(first, last - first + 1);
        if (line.size() < 25 || line.rfind("TEST_CASE(", 0) == 0 || line.rfind("name = ", 0) == 0) continue;
        lines.push_back(line);
    }
    return lines;
}

// What no student may ever see: the hidden tests, the rubric and /etc/shadow (when this process can read it).
std::vector<std::pair<std::string, std::string>> secrets(const Assignment& assignment) {
    std::vector<std::pair<std::string, std::string>> found;
    std::vector<std::string> files = assignment.hiddenTests;
    files.push_back(assignment.rubric);
    for (const std::string& file : files) {
        if (!fs::exists(file)) continue;
        for (const std::string& line : telltaleLines(readFile(file))) found.push_back({fs::path(file).filename(), line});
    }
    std::ifstream shadow("/etc/shadow");
    for (std::string line; std::getline(shadow, line);) {
        if (line.size() >= 8) found.push_back({"/etc/shadow", line});
    }
    return found;
}

std::vector<std::string> leaks(const std::vector<std::pair<std::string, std::string>>& secret, const std::string& seen) {
    std::vector<std::string> out;
    for (const auto& [file, line] : secret) {
        if (seen.find(line) != std::string::npos) out.push_back("it shows a line of " + file + ": " + printable(line));
    }
    return out;
}

// Every string a JSON document holds, decoded, one per line: the text a reader of it sees.
void jsonStrings(const nlohmann::json& j, std::string& out) {
    if (j.is_string()) {
        out += j.get<std::string>() + "\n";
    } else if (j.is_structured()) {
        for (const auto& item : j) jsonStrings(item, out);
    }
}

// Control characters a terminal would act on: C0 but newline and tab, DEL, and C1 (as UTF-8).
std::string firstControl(const std::string& text) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) return "byte " + std::to_string(c) + " at " + std::to_string(i);
        if (c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
            static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
            return "a C1 control at " + std::to_string(i);
        }
    }
    return "";
}


int check(const Manifest& manifest, const Assignment& assignment, const simlab::Rubric& rubric,
          const std::string& path) {
    const Case c = loadCase(assignment, rubric, path);
    if (c.skipped) {
        std::cout << c.name << ": a folder simlab grade skips; graded only as part of a class\nOK: as expected\n";
        return 0;
    }
    TempDir dir("simlab-corpus-");
    writeCase(c, dir.path() + "/student", dir.path());
    GradeOptions options;
    options.includeHidden = true;
    options.onlyTests = c.tests;
    const GradeReport report =
        gradeFolder(Builder(manifest), assignment, rubric, dir.path() + "/student", false, false, options);
    const std::string text = renderText(report);
    std::cout << c.name << ": " << c.description << "\n" << text << "(the tests its edit concerns: " << c.tests.size()
              << " of " << rubric.tests.size() << "; a class grades them all)\n";

    std::vector<std::string> mismatches = compare(c, report.tests, std::nullopt, report.status, text, false);
    for (const std::string& leak : leaks(secrets(assignment), text)) mismatches.push_back(leak);
    for (const std::string& m : mismatches) std::cout << "MISMATCH: " << m << "\n";
    std::cout << (mismatches.empty() ? "OK: as expected\n" : "FAILED\n");
    return mismatches.empty() ? 0 : 1;
}

// Counts connections to 127.0.0.1:port while it lives.
class Listener {
public:
    explicit Listener(int port) {
        fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
        const int yes = 1;
        ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(static_cast<uint16_t>(port));
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || ::listen(fd_, 16) != 0) {
            throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(port));
        }
        thread_ = std::thread([this] {
            while (!stop_) {
                pollfd p{fd_, POLLIN, 0};
                if (::poll(&p, 1, 100) > 0) {
                    const int client = ::accept(fd_, nullptr, nullptr);
                    if (client >= 0) {
                        ++connections_;
                        ::close(client);
                    }
                }
            }
        });
    }
    ~Listener() {
        stop_ = true;
        thread_.join();
        ::close(fd_);
    }
    int connections() const { return connections_; }

private:
    int fd_ = -1;
    std::atomic<bool> stop_{false};
    std::atomic<int> connections_{0};
    std::thread thread_;
};

std::string marker(const std::string& student) { return "corpus student " + student + " wrote this file"; }

// The cells of a CSV document, quotes undone.
std::vector<std::vector<std::string>> csvRows(const std::string& text) {
    std::vector<std::vector<std::string>> rows(1);
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (quoted) {
            if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') cell += '"', ++i;
            else if (ch == '"') quoted = false;
            else cell += ch;
        } else if (ch == '"') {
            quoted = true;
        } else if (ch == ',') {
            rows.back().push_back(cell), cell.clear();
        } else if (ch == '\n') {
            rows.back().push_back(cell), cell.clear();
            rows.emplace_back();
        } else {
            cell += ch;
        }
    }
    if (!rows.back().empty() || !cell.empty()) rows.back().push_back(cell);
    else rows.pop_back();
    return rows;
}

// Processes named `name` (their comm) on this machine, zombies aside.
int processesNamed(const std::string& name) {
    int count = 0;
    std::error_code error;
    for (auto it = fs::directory_iterator("/proc", error); !error && it != fs::directory_iterator(); it.increment(error)) {
        std::ifstream comm(it->path() / "comm"), stat(it->path() / "stat");
        std::string line, all;
        if (!std::getline(comm, line) || line != name || !std::getline(stat, all)) continue;
        const std::size_t close = all.rfind(')');
        if (close != std::string::npos && close + 2 < all.size() && all[close + 2] != 'Z') ++count;
    }
    return count;
}

// Docker's default capabilities (no CAP_SYS_ADMIN), as in Gradescope's and PrairieLearn's containers.
const char* const kDockerCapabilities =
    "-all,+chown,+dac_override,+fowner,+fsetid,+kill,+setgid,+setuid,+setpcap,+net_bind_service,+net_raw,"
    "+sys_chroot,+mknod,+audit_write,+setfcap";

// The first folder on the way to `path` that other users may not pass through; empty if there is none.
std::string closedToOthers(const std::string& path) {
    fs::path walked;
    for (const fs::path& part : fs::absolute(path).lexically_normal().parent_path()) {
        walked /= part;
        struct stat info {};
        if (::stat(walked.c_str(), &info) == 0 && !(info.st_mode & S_IXOTH)) return walked.string();
    }
    return "";
}

// What ctest counts as skipped (SKIP_RETURN_CODE): the class cannot be graded in this mode from where the build lies.
constexpr int kSkipped = 77;

// Each case's student as `out` (simlab grade's --out) has them: outcomes, score, status and text against the case's
// expectations, and no report holding another student's file or a secret. What differs goes to `problems`.
void compareGraded(const Assignment& assignment, const std::vector<Case>& cases, const std::string& out,
                   std::vector<std::string>& problems) {
    const auto secret = secrets(assignment);
    for (const Case& c : cases) {
        if (c.skipped) continue;
        const std::string student = out + "/students/" + c.folder;
        if (!fs::exists(student + "/results.json")) {
            problems.push_back(c.name + ": no results.json");
            continue;
        }
        const std::string results = readFile(student + "/results.json");
        const std::string feedback = readFile(student + "/feedback.md");
        if (!isValidUtf8(results)) problems.push_back(c.name + ": results.json is not valid UTF-8");
        const nlohmann::json json = nlohmann::json::parse(results, nullptr, false);
        if (json.is_discarded()) {
            problems.push_back(c.name + ": results.json is not JSON");
            continue;
        }
        if (const std::string control = firstControl(feedback); !control.empty()) {
            problems.push_back(c.name + ": feedback.md holds a control character: " + control);
        }
        std::vector<TestResult> tests;
        for (const nlohmann::json& t : json.at("tests")) {
            TestResult r;
            r.name = t.at("name");
            r.outcome = outcomeNamed(t.at("extra_data").at("outcome"));
            tests.push_back(r);
        }
        const std::string said = json.at("extra_data").value("status", "");
        const std::optional<SubmissionStatus> status = statusNamed(said);
        if (!status) {
            problems.push_back(c.name + ": results.json's status '" + said + "' is not one simlab names");
            continue;
        }
        std::string seen = feedback;
        jsonStrings(json, seen);
        std::vector<std::string> mismatches = compare(c, tests, json.at("score"), *status, seen);
        for (const Case& other : cases) {
            if (other.name != c.name && (results + feedback).find(marker(other.name)) != std::string::npos) {
                mismatches.push_back("its report holds " + other.name + "'s file");
            }
        }
        for (const std::string& leak : leaks(secret, results + seen)) mismatches.push_back(leak);
        std::cout << (mismatches.empty() ? "OK       " : "MISMATCH ") << c.name << ": " << points(json.at("score"))
                  << " (expected " << points(c.score) << ")\n";
        for (const std::string& m : mismatches) problems.push_back(c.name + ": " + m);
    }
}

int gradeAsClass(const Assignment& assignment, const simlab::Rubric& rubric, const std::vector<std::string>& paths,
                 const std::string& simlab, int jobs, const std::vector<std::string>& environment,
                 bool dockerCapabilities, const std::string& keep) {
    std::vector<Case> cases;
    for (const std::string& path : paths) cases.push_back(loadCase(assignment, rubric, path));
    TempDir dir("simlab-class-");
    const std::string submissions = dir.path() + "/submissions", out = dir.path() + "/grades";
    fs::create_directories(submissions);
    for (const Case& c : cases) {
        Case marked = c;
        const auto source = marked.files.find(assignment.source);
        if (source != marked.files.end() && source->second.symlink.empty() && !source->second.fifo &&
            source->second.sparse == 0) {
            source->second.text += "\n// " + marker(c.name) + "\n";
        }
        writeCase(marked, submissions + "/" + c.folder, submissions);
    }

    Listener listener(47810);
    ProcessRequest request;
    request.argv = {simlab, "grade", assignment.id, submissions, "--out", out, "--jobs", std::to_string(jobs)};
    if (dockerCapabilities) {
        request.argv.insert(request.argv.begin(),
                            {"/usr/bin/setpriv", std::string("--bounding-set=") + kDockerCapabilities, "--inh-caps=-all"});
    }
    request.env = childEnvironment(environment);
    request.workDir = dir.path();
    request.limits.wallSeconds = request.limits.cpuSeconds = 3000;
    request.limits.memoryMiB = 1 << 20;
    request.limits.processes = 4096;
    request.limits.fileMiB = 4096;
    request.limits.outputKiB = 16 * 1024;
    request.keepOutput = 1 << 20;
    const ProcessResult batch = runProcess(request);
    std::cout << printable(batch.output, true);

    // As root without bubblewrap each tool runs as a throwaway user, who must reach the build: below a folder closed
    // to other users simlab refuses, in one line naming it, and grades nobody. The class is then skipped.
    const bool throwawayUsers = ::geteuid() == 0 && std::find(environment.begin(), environment.end(),
                                                              "SIMLAB_NO_BUBBLEWRAP=1") != environment.end();
    if (const std::string closed = closedToOthers(simlab); throwawayUsers && !closed.empty()) {
        const bool said = batch.exitCode == 2 && batch.output.find("cannot reach") != std::string::npos &&
                          batch.output.find("(" + closed + " is closed to others)") != std::string::npos &&
                          batch.output.find("chmod o+x " + closed + ",") != std::string::npos;
        if (!said || fs::exists(out + "/gradebook.csv")) {
            std::cout << "FAILED: the build lies below " << closed
                      << ", which other users may not enter, and simlab did not refuse in one line naming it\n";
            return 1;
        }
        std::cout << "OK: simlab refused, naming " << closed << "\nskipped: the class in this mode (the build lies below "
                  << closed << ", which other users may not enter)\n";
        return kSkipped;
    }

    std::vector<std::string> problems;
    if (!batch.exitedCleanly()) problems.push_back("simlab grade did not complete (status " + std::to_string(batch.exitCode) + ")");
    // What a submission started must end with its test (tests/corpus/apple/hostile/daemon-and-reader.toml).
    if (const int left = processesNamed("simlab-daemon"); left > 0) {
        problems.push_back(std::to_string(left) + " process(es) a submission left behind outlived the grading");
    }
    if (listener.connections() > 0) {
        problems.push_back(std::to_string(listener.connections()) + " connection(s) reached 127.0.0.1:47810");
    }
    if (const std::string control = firstControl(batch.output); !control.empty()) {
        problems.push_back("simlab's terminal output holds a control character: " + control);
    }
    // simlab's own memory, not its tests' (a test may hold gigabytes: memory-tree.toml).
    std::printf("simlab grade: %.1f s, peak memory %ld MiB\n", batch.wallSeconds, batch.ownPeakKiB / 1024);
    if (batch.ownPeakKiB > 512 * 1024) problems.push_back("simlab used " + std::to_string(batch.ownPeakKiB / 1024) + " MiB");

    // One gradebook row per student, none twice, no cell a spreadsheet would run; skipped folders listed.
    const std::vector<std::vector<std::string>> gradebook = csvRows(fs::exists(out + "/gradebook.csv") ? readFile(out + "/gradebook.csv") : "");
    std::multiset<std::string> ids;
    std::map<std::string, std::string> statusOf;
    for (std::size_t r = 1; r < gradebook.size(); ++r) {
        if (gradebook[r].size() < 4) continue;
        ids.insert(gradebook[r][0]);
        statusOf[gradebook[r][0]] = gradebook[r][3];
    }
    for (const std::string& csv : {std::string("gradebook.csv"), std::string("summary.csv")}) {
        for (const auto& row : csvRows(fs::exists(out + "/" + csv) ? readFile(out + "/" + csv) : "")) {
            for (const std::string& cell : row) {
                if (!cell.empty() && std::string("=+-@\t\r").find(cell[0]) != std::string::npos) {
                    problems.push_back(csv + " has a cell a spreadsheet would read as a formula: " + printable(cell));
                }
            }
        }
    }
    std::size_t graded = 0;
    for (const Case& c : cases) {
        // What simlab writes for this student's id: printable, then neutralized, as its one CSV writer does.
        const std::string id = csvRows(csvCell(printable(c.folder)) + "\n").front().front();
        if (c.skipped) {
            if (ids.count(id)) problems.push_back(c.name + ": a skipped folder has a gradebook row");
            if (batch.output.find("skipped " + printable(c.folder)) == std::string::npos) {
                problems.push_back(c.name + ": its folder is not listed as skipped");
            }
            continue;
        }
        ++graded;
        if (ids.count(id) != 1) problems.push_back(c.name + ": " + std::to_string(ids.count(id)) + " gradebook rows");
        if (c.status && statusOf[id] != statusName(*c.status)) {
            problems.push_back(c.name + ": status '" + statusOf[id] + "', expected '" + statusName(*c.status) + "'");
        }
    }
    if (ids.size() != graded) problems.push_back("the gradebook has " + std::to_string(ids.size()) + " rows");

    compareGraded(assignment, cases, out, problems);
    if (!keep.empty() && fs::is_directory(out)) {
        const fs::path kept = fs::absolute(keep);
        fs::remove_all(kept);
        fs::create_directories(kept.parent_path());
        fs::copy(out, kept, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
    }
    for (const std::string& p : problems) std::cout << "MISMATCH: " << p << "\n";
    std::cout << (problems.empty() ? "OK: every student as expected\n" : "FAILED\n");
    return problems.empty() ? 0 : 1;
}


// Compares a class graded into `grades` (simlab grade of the materialized cases: the sample class) with the cases.
int compareClass(const Assignment& assignment, const simlab::Rubric& rubric, const std::vector<std::string>& paths,
                 const std::string& grades) {
    std::vector<Case> cases;
    for (const std::string& path : paths) cases.push_back(loadCase(assignment, rubric, path));
    std::vector<std::string> problems;
    compareGraded(assignment, cases, grades, problems);
    for (const std::string& p : problems) std::cout << "MISMATCH: " << p << "\n";
    std::cout << (problems.empty() ? "OK: every student as expected\n" : "FAILED\n");
    return problems.empty() ? 0 : 1;
}

// ---- the isolation's invariants ------------------------------------------------------------------------------------

// What a test may read, for the witness's walk (witness.inc's kReach): where to start besides / (the top of the
// machine as root sees it, simlab's places, the temporary folder), the system, simlab's places and the name prefix
// of gradings' folders, what a probe is lent (limits only: what any tool is, lentOfPlaces), and "M" where files are
// kept apart by their modes alone.
std::string reachLiteral(const Manifest& manifest) {
    const SandboxSupport& sandbox = sandboxSupport();
    const bool modesAlone = !sandbox.bubblewrap && !sandbox.landlock;
    std::vector<std::string> lines;
    // Where to start: the folders two levels down from / and around each place (the folders on the way to it, it,
    // and what is in it), by the names root sees - a sandbox may let a test enter a folder it may not list (Landlock
    // grants /usr's entries one by one where a place lies among them).
    std::set<std::string> starts;
    const auto folders = [](const std::string& dir) {
        std::vector<std::string> found;
        std::error_code error;
        for (auto it = fs::directory_iterator(dir, error); !error && it != fs::directory_iterator(); it.increment(error)) {
            if (it->is_directory(error) && !it->is_symlink(error)) found.push_back(it->path().string());
        }
        return found;
    };
    for (const std::string& top : folders("/")) {
        if (top == "/proc" || top == "/sys") continue;
        starts.insert(top);
        for (const std::string& below : folders(top)) starts.insert(below);
    }
    const char* tmp = std::getenv("TMPDIR");
    const std::string temporary = tmp && *tmp ? tmp : "/tmp";
    starts.insert(temporary);
    for (const std::string& place : places()) {
        for (fs::path up = place; up.has_relative_path(); up = up.parent_path()) starts.insert(up.string());
        for (const std::string& below : folders(place)) starts.insert(below);
    }
    for (const std::string& start : starts) lines.push_back("S" + start);
    for (const auto* list : {&systemFolders(), &systemFiles(), &systemDevices()}) {
        for (const std::string& path : *list) lines.push_back("A" + path);
    }
    for (const std::string& path : notTheSystems()) lines.push_back("X" + path);
    for (const std::string& place : places()) lines.push_back("P" + place);
    lines.push_back("T" + temporary + "/simlab-");
    if (modesAlone) {
        for (const std::string& path : lentOfPlaces(manifest)) lines.push_back("L" + path);
        lines.push_back("M");
    } else {
        lines.push_back("L" + manifest.probeHost);
    }
    std::string literal = "\"";
    for (const std::string& line : lines) {
        for (const char c : line) {
            if (c == '"' || c == '\\') literal += '\\';
            literal += c;
        }
        literal += "\\n";
    }
    return literal + "\"";
}

// The walks' records, R{d=FOLDERS;f=FILES;o=OUTSIDE;b=BOUNDED;p=PATH|PATH...}, that the report holds, in its order
// (a case of random calls has two: the walk of a process of the calls', and the test's own).
struct Walk {
    unsigned long folders = 0, files = 0, outside = 0;
    bool bounded = false;
    std::vector<std::string> first;
};

std::vector<Walk> walkRecords(const std::string& text) {
    std::vector<Walk> walks;
    for (std::size_t at = text.find("R{d="); at != std::string::npos; at = text.find("R{d=", at + 4)) {
        // A record the report cut (a test's reason is at most 400 bytes) ends with its line: its counts came first.
        const std::size_t end = std::min(text.find_first_of("}\n", at), text.size());
        Walk w;
        std::istringstream fields(text.substr(at + 2, end - at - 2));
        for (std::string field; std::getline(fields, field, ';');) {
            const std::size_t eq = field.find('=');
            if (eq == std::string::npos) continue;
            const std::string key = field.substr(0, eq), value = field.substr(eq + 1);
            if (key == "d") w.folders = std::stoul(value);
            if (key == "f") w.files = std::stoul(value);
            if (key == "o") w.outside = std::stoul(value);
            if (key == "b") w.bounded = value == "1";
            if (key == "p") {
                std::istringstream paths(value);
                for (std::string path; std::getline(paths, path, '|');) w.first.push_back(path);
            }
        }
        walks.push_back(w);
    }
    return walks;
}

// ---- random system calls (tests/corpus/calls.inc) -------------------------------------------------------------------

// A folder of the corpus's own in the shared temporary folder, with a file in it, that the random calls aim at: both
// readable by all, neither writable but by their owner. Removed when it goes.
class Bait {
public:
    Bait() {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/fzbait-XXXXXX";
        if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make the bait folder in " + pattern);
        folder_ = pattern;
        ::chmod(folder_.c_str(), 0755);
        writeFileAtomically(folder_ + "/bait", "the corpus's bait: random calls must leave it as it is\n");
        ::chmod((folder_ + "/bait").c_str(), 0644);
    }
    ~Bait() {
        std::error_code ignored;
        fs::remove_all(folder_, ignored);
    }
    const std::string& folder() const { return folder_; }

private:
    std::string folder_;
};

// A positive number from the environment variable `name`, else `fallback`.
unsigned long long setting(const char* name, unsigned long long fallback) {
    const char* value = std::getenv(name);
    const unsigned long long n = value ? std::strtoull(value, nullptr, 10) : 0;
    return n > 0 ? n : fallback;
}

// The paths the random calls aim at: where a test may write (its folder), the machine's shared temporary folders and
// the bait (named fzcall-N, to be looked for after), simlab's places and the system's secrets.
std::vector<std::string> callPaths(const Manifest& manifest, const Assignment& assignment, const std::string& bait) {
    std::vector<std::string> paths = {"fzcall-1", "./fzcall-2", "../fzcall-3", "/tmp/fzcall-4", "/var/tmp/fzcall-5",
                                      "/dev/shm/fzcall-6", "/run/lock/fzcall-7", bait + "/fzcall-8", bait,
                                      bait + "/bait", ".", "..", "", "/", "/etc/passwd", "/etc/shadow", "/etc",
                                      "/proc/self/mem", "/proc/1/root", "/dev/kmsg", "/dev/tty", "/dev/null", "/root",
                                      "/home", assignment.rubric, assignment.solution, assignment.judge, manifest.path,
                                      manifest.sourceDir, manifest.buildDir};
    if (!assignment.hiddenTests.empty()) paths.push_back(assignment.hiddenTests.front());
    if (const char* home = std::getenv("HOME")) paths.push_back(std::string(home) + "/fzcall-9");
    return paths;
}

// tests/corpus/calls.inc with its lists written in: the students' filter's calls by number, the paths, the draw.
std::string callsCode(const Manifest& manifest, const Assignment& assignment, const std::string& bait,
                      unsigned long long seed) {
    std::string code = readFile(SIMLAB_CORPUS_DIR "/calls.inc");
    filter::prepareCallNames();
    const std::vector<std::string> allowedNames = filter::allowedCalls();
    const std::vector<std::string> refusedNames = filter::refusedCalls();
    std::string allowed, refused;
    for (long n = 0; n < 1024; ++n) {
        const char* name = filter::callName(n);
        if (!name) continue;
        if (std::count(allowedNames.begin(), allowedNames.end(), name)) allowed += (allowed.empty() ? "" : ", ") + std::to_string(n);
        if (std::count(refusedNames.begin(), refusedNames.end(), name)) refused += (refused.empty() ? "" : ", ") + std::to_string(n);
    }
    std::string paths;
    for (const std::string& path : callPaths(manifest, assignment, bait)) {
        paths += paths.empty() ? "\"" : ", \"";
        for (const char c : path) {
            if (c == '"' || c == '\\') paths += '\\';
            paths += c;
        }
        paths += '"';
    }
    const std::map<std::string, std::string> values = {
        {"{allowed}", allowed}, {"{refused}", refused}, {"{paths}", paths}, {"{seed}", std::to_string(seed)},
        {"{count}", std::to_string(setting("SIMLAB_CALLS", 20000))},
        {"{millis}", std::to_string(setting("SIMLAB_CALLS_MILLIS", 1500))}};
    for (const auto& [name, value] : values) {
        for (std::size_t at = code.find(name); at != std::string::npos; at = code.find(name, at + value.size())) {
            code.replace(at, name.size(), value);
        }
    }
    return code;
}

// The random calls' record, C{n=...;a=...;...;seed=...}: each field's text by its name.
std::map<std::string, std::string> callsRecord(const std::string& text) {
    std::map<std::string, std::string> fields;
    const std::size_t at = text.find("C{n=");
    const std::size_t end = at == std::string::npos ? at : text.find('}', at);
    if (end == std::string::npos) return fields;
    std::istringstream in(text.substr(at + 2, end - at - 2));
    for (std::string field; std::getline(in, field, ';');) {
        const std::size_t eq = field.find('=');
        if (eq != std::string::npos) fields[field.substr(0, eq)] = field.substr(eq + 1);
    }
    return fields;
}

// What of the host a case's code could change: the entries of the shared temporary folders (by owner), the
// processes (by real user), the machine's name, and the files the calls aim at (their kind, owner, mode, size,
// time and bytes).
struct HostState {
    std::map<std::string, uid_t> shared;
    std::map<pid_t, uid_t> processes;
    std::string machine;
    std::map<std::string, std::string> files;
};

std::string fileState(const std::string& path) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) return "(none)";
    std::string state = std::to_string(info.st_mode) + " " + std::to_string(info.st_uid) + ":" +
                        std::to_string(info.st_gid) + " " + std::to_string(info.st_size) + " " +
                        std::to_string(info.st_mtim.tv_sec) + "." + std::to_string(info.st_mtim.tv_nsec);
    if (S_ISREG(info.st_mode) && info.st_size < (1 << 24)) state += " " + sha256Hex(readFile(path));
    return state;
}

HostState hostState(const std::vector<std::string>& files) {
    HostState h;
    for (const char* folder : {"/tmp", "/var/tmp", "/dev/shm", "/run/lock"}) {
        std::error_code error;
        for (auto it = fs::directory_iterator(folder, error); !error && it != fs::directory_iterator(); it.increment(error)) {
            struct stat info {};
            if (::lstat(it->path().c_str(), &info) == 0) h.shared[it->path().string()] = info.st_uid;
        }
    }
    if (DIR* proc = ::opendir("/proc")) {
        while (const struct dirent* e = ::readdir(proc)) {
            if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
            std::ifstream status(std::string("/proc/") + e->d_name + "/status");
            for (std::string line; std::getline(status, line);) {
                if (line.rfind("Uid:", 0) == 0) {
                    h.processes[static_cast<pid_t>(std::atol(e->d_name))] = static_cast<uid_t>(std::stoul(line.substr(4)));
                    break;
                }
            }
        }
        ::closedir(proc);
    }
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    h.machine = name;
    for (const std::string& file : files) h.files[file] = fileState(file);
    return h;
}

// What changed on the host between `before` and `after` that a test's code did: a file a call made (fzcall-N) or
// the test's users (`users`: those its processes ran as, neither root nor simlab's own) left in a shared temporary
// folder, a process of theirs left, another machine name, a watched file changed.
std::vector<std::string> hostChanges(const HostState& before, const HostState& after, const std::set<uid_t>& users) {
    std::vector<std::string> changes;
    for (const auto& [path, owner] : after.shared) {
        const bool made = fs::path(path).filename().string().rfind("fzcall-", 0) == 0;
        if (!before.shared.count(path) && (made || users.count(owner))) {
            changes.push_back("left on the host: " + path + " (uid " + std::to_string(owner) + ")");
        }
    }
    for (const auto& [pid, owner] : after.processes) {
        if (users.count(owner)) {
            changes.push_back("a process of the test's user (uid " + std::to_string(owner) + ") is left: " +
                              std::to_string(pid));
        }
    }
    if (after.machine != before.machine) changes.push_back("the machine's name changed to " + printable(after.machine));
    for (const auto& [file, state] : before.files) {
        if (after.files.at(file) != state) changes.push_back("changed on the host: " + file);
    }
    return changes;
}

// One record of the witness: W{e=ENTRY,ENTRY...;u=UID/EUID;c=EFF/PRM/INH/AMB/BND;nnp=N} (capabilities in
// hexadecimal): the entry points that saw one state.
struct Record {
    std::vector<std::string> entries;
    unsigned long uid = 0, euid = 0;
    std::map<std::string, unsigned long> caps;  // effective, permitted, inheritable, ambient, bounding
};

std::vector<Record> records(const std::string& text) {
    std::vector<Record> found;
    std::set<std::string> distinct;
    for (std::size_t at = text.find("W{e="); at != std::string::npos; at = text.find("W{e=", at + 4)) {
        const std::size_t end = text.find('}', at);
        if (end == std::string::npos) break;
        const std::string body = text.substr(at + 4, end - at - 4);
        if (!distinct.insert(body).second) continue;
        Record r;
        std::istringstream fields(body);
        std::string field;
        bool first = true;
        while (std::getline(fields, field, ';')) {
            if (first) {
                std::istringstream names(field);
                for (std::string name; std::getline(names, name, ',');) r.entries.push_back(name);
                first = false;
                continue;
            }
            const std::size_t eq = field.find('=');
            if (eq == std::string::npos) continue;
            const std::string key = field.substr(0, eq), value = field.substr(eq + 1);
            if (key == "u") {
                r.uid = std::stoul(value.substr(0, value.find('/')));
                r.euid = std::stoul(value.substr(value.find('/') + 1));
            } else if (key == "c") {
                std::istringstream sets(value);
                std::string bits;
                for (const char* set : {"effective", "permitted", "inheritable", "ambient", "bounding"}) {
                    if (std::getline(sets, bits, '/')) r.caps[set] = std::stoul(bits, nullptr, 16);
                }
            }
        }
        found.push_back(r);
    }
    return found;
}

// The wall-clock net of an invariant's test (a rubric's is 30 s or so): the walk's reads of the whole system, beside
// other work, without the grade stalling.
constexpr double kInvariantWallSeconds = 180;

// Grades each case with the object check off, in the sandbox this machine and its environment give
// (SIMLAB_NO_BUBBLEWRAP, SIMLAB_NO_LANDLOCK, SIMLAB_NO_TEST_SERVER; a capability set from setpriv; an installed
// simlab's manifest from SIMLAB_MANIFEST), on one test, and reads the witness's records from the report: who each
// entry point ran as, and what the walk of a test's call could read.
int invariants(const Manifest& manifest, const Assignment& assignment, const simlab::Rubric& rubric,
               const std::vector<std::string>& paths) {
    const SandboxSupport& sandbox = sandboxSupport();
    const bool root = ::geteuid() == 0;
    std::cout << "sandbox: " << sandbox.summary << (testServers() ? "; tests forked by a probe's server" : "; a probe per test")
              << "\nmanifest: " << manifest.path << "\n";
    // Where files are kept apart by their modes alone, simlab runs hidden tests only once nothing of its places but
    // what is lent opens for a throwaway user; until then (it refuses, in one line) a visible test's reading them is
    // that mode's known limit, and the walk must show that the refusal was right.
    std::string refusal;
    if (!sandbox.bubblewrap && !sandbox.landlock) {
        refusal = placesExposed(manifest);
        std::cout << "limits only: "
                  << (refusal.empty() ? "nothing of simlab's places opens for a throwaway user but what it is lent"
                                      : "simlab refuses hidden tests here: " + refusal)
                  << "\n";
    }
    int failures = 0;
    for (const std::string& path : paths) {
        const Case c = loadCase(assignment, rubric, path);
        const auto source = c.files.find(assignment.source);
        const bool calls = source != c.files.end() && source->second.text.find("simlab_calls::tryCalls") != std::string::npos;
        // Where a test runs as the user who started simlab with files kept apart by their modes alone, a call at
        // random could change that user's files: not tried there.
        if (calls && !root && !sandbox.bubblewrap && !sandbox.landlock) {
            std::cout << "skipped  " << c.name << ": random calls where a test runs as you, its files kept apart by "
                                                  "their modes alone (they could change your files)\n";
            continue;
        }
        const std::vector<std::string> watched = {gBait, gBait + "/bait", assignment.rubric, assignment.solution,
                                                  assignment.hiddenTests.empty() ? manifest.path : assignment.hiddenTests.front(),
                                                  manifest.path};
        const HostState before = hostState(watched);
        TempDir dir("simlab-invariant-");
        writeCase(c, dir.path() + "/student", dir.path());
        GradeOptions options;
        options.checkObject = false;
        options.onlyTests = {rubric.tests.front().name};
        // A walk lists every folder of the system a test can reach (some 20,000 folders, 170,000 files), reading
        // them from disk where no cache holds them: on a machine busy with other work that can outlast the rubric's
        // wall-clock net for a student's test while using a few seconds of CPU. The net is widened; the CPU limit,
        // which is what a runaway test meets, stays the rubric's.
        simlab::Limits limits = rubric.limits;
        limits.wallSeconds = std::max(limits.wallSeconds, kInvariantWallSeconds);
        options.limits = limits;
        const GradeReport report =
            gradeFolder(Builder(manifest), assignment, rubric, dir.path() + "/student", false, false, options);
        const std::string text = renderText(report);
        std::vector<std::string> problems;
        const std::vector<Record> made = records(text);
        bool entryRan = false;
        std::set<uid_t> users;  // the test's own users (none where it runs as simlab's)
        for (const Record& r : made) {
            entryRan = entryRan || std::find(r.entries.begin(), r.entries.end(), c.invariantEntry) != r.entries.end();
            std::string where;
            for (const std::string& e : r.entries) where += (where.empty() ? "'" : ", '") + e + "'";
            if (r.uid == 0 || r.euid == 0) problems.push_back(where + " ran as root");
            for (const unsigned long uid : {r.uid, r.euid}) {
                if (uid != 0 && uid != ::geteuid()) users.insert(static_cast<uid_t>(uid));
            }
            for (const auto& [set, bits] : r.caps) {
                // The bounding set is a user's own business when simlab does not run as root.
                if (bits != 0 && (set != "bounding" || root)) {
                    char hex[32];
                    std::snprintf(hex, sizeof hex, "%#lx", bits);
                    problems.push_back(where + " held capabilities (" + set + " set " + hex + ")");
                }
            }
        }
        std::string walkLine;
        for (const Walk& walked : walkRecords(text)) {
            std::string line = "walk: " + std::to_string(walked.folders) + " folders listed, " +
                               std::to_string(walked.files) + " files readable, " + std::to_string(walked.outside) +
                               " outside what a test may read";
            std::string first;
            for (const std::string& f : walked.first) first += (first.empty() ? "" : ", ") + f;
            if (walked.folders == 0 || walked.files == 0) problems.push_back("the walk read nothing: " + line);
            if (walked.bounded) problems.push_back("the walk stopped at its bound: " + line);
            if (walked.outside > 0 && refusal.empty()) problems.push_back(line + ": " + first);
            if (walked.outside > 0 && !refusal.empty()) {
                line += " (simlab refuses hidden tests here" + (first.empty() ? "" : ": " + first) + ")";
            }
            walkLine += (walkLine.empty() ? "" : "; ") + line;
        }
        if (calls) {
            const std::map<std::string, std::string> tally = callsRecord(text);
            const auto field = [&](const char* key) {
                const auto found = tally.find(key);
                return found == tally.end() ? std::string("?") : found->second;
            };
            if (tally.empty() || field("n") == "0") problems.push_back("no random call was made");
            if (field("x") != "0") {
                problems.push_back("a call the students' filter refuses went through (its number and what it "
                                   "returned): " + field("x"));
            }
            if (walkRecords(text).size() < 2) problems.push_back("no process of the random calls lived to walk after them");
            walkLine = "random calls: " + field("n") + " tried (" + field("a") + " the filter allows, " + field("r") +
                       " it refuses, " + field("u") + " of neither list; " + field("ok") + " went through, " +
                       field("e") + " refused with EPERM, " + field("x") + " otherwise) in " + field("k") +
                       " processes (" + field("s") + " ended by SIGSYS), " + field("ms") + " ms, seed " + field("seed") +
                       "; " + walkLine;
        }
        for (const std::string& change : hostChanges(before, hostState(watched), users)) problems.push_back(change);
        if (made.empty()) problems.push_back("no record of the witness in the report: " + statusName(report.status));
        if (c.invariantRuns && !entryRan) problems.push_back("'" + c.invariantEntry + "' never ran");
        if (!c.invariantRuns && entryRan) problems.push_back("'" + c.invariantEntry + "' ran, and must not");
        if (problems.empty()) {
            std::set<unsigned long> users;
            std::size_t entries = 0;
            for (const Record& r : made) {
                users.insert(r.uid);
                entries += r.entries.size();
            }
            std::cout << "OK       " << c.name << ": "
                      << (c.invariantRuns ? "'" + c.invariantEntry + "' ran" : "'" + c.invariantEntry + "' never ran") << "; "
                      << entries << " entry point(s) recorded, as uid " << *users.begin()
                      << (users.size() > 1 ? " and others" : "") << ", with no capability"
                      << (walkLine.empty() ? "" : "; " + walkLine) << "\n";
        } else {
            ++failures;
            std::cout << "FAILED   " << c.name << ":\n";
            for (const std::string& p : problems) std::cout << "    " << p << "\n";
            std::cout << text;
        }
    }
    std::cout << (failures == 0 ? "OK: no student code ran with privilege or read beyond what a test may read\n"
                                : "FAILED\n");
    return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"The corpus of sample submissions with their expected scores.", "simlab-corpus"};
    app.require_subcommand(1);
    std::string assignmentId, out;
    std::vector<std::string> cases;
    CLI::App* materializeCommand = app.add_subcommand("materialize", "Write each case's submission file.");
    materializeCommand->add_option("assignment", assignmentId)->required();
    materializeCommand->add_option("cases", cases)->required()->check(CLI::ExistingFile);
    materializeCommand->add_option("--out", out)->required();
    CLI::App* checkCommand = app.add_subcommand("check", "Grade one case and compare with its expectations.");
    checkCommand->add_option("assignment", assignmentId)->required();
    checkCommand->add_option("case", cases)->required()->expected(1)->check(CLI::ExistingFile);
    std::string simlab;
    int jobs = 2;
    CLI::App* classCommand = app.add_subcommand("class", "Grade the cases as one class with simlab grade and compare.");
    classCommand->add_option("assignment", assignmentId)->required();
    classCommand->add_option("cases", cases)->required()->check(CLI::ExistingFile);
    classCommand->add_option("--simlab", simlab)->required()->check(CLI::ExistingFile);
    classCommand->add_option("--jobs", jobs);
    std::vector<std::string> environment;
    bool dockerCapabilities = false;
    classCommand->add_option("--env", environment, "NAME=VALUE for simlab grade (SIMLAB_NO_BUBBLEWRAP=1, say)");
    classCommand->add_flag("--docker-capabilities", dockerCapabilities,
                           "run simlab grade as root with Docker's default capabilities only (setpriv)");
    std::string keep;
    classCommand->add_option("--keep", keep, "leave the grades (simlab grade's --out) in this folder");
    std::string grades;
    CLI::App* compareCommand = app.add_subcommand("compare", "Compare a class graded into --grades with the cases.");
    compareCommand->add_option("assignment", assignmentId)->required();
    compareCommand->add_option("cases", cases)->required()->check(CLI::ExistingFile);
    compareCommand->add_option("--grades", grades, "simlab grade's --out")->required()->check(CLI::ExistingDirectory);
    CLI::App* invariantsCommand =
        app.add_subcommand("invariants", "Grade each case with the object check off and check the witness's records.");
    invariantsCommand->add_option("assignment", assignmentId)->required();
    invariantsCommand->add_option("cases", cases)->required()->check(CLI::ExistingFile);
    CLI11_PARSE(app, argc, argv);
    try {
        const Manifest manifest = loadManifest();
        gSourceDir = manifest.sourceDir;
        gBuildDir = manifest.buildDir;
        const Assignment& assignment = manifest.find(assignmentId);
        // The witness knows what a test may read once the lab's places are known (Manifest::find adds a lab's).
        gWitness = readFile(SIMLAB_CORPUS_DIR "/witness.inc");
        const std::size_t at = gWitness.find("{reach}");
        if (at != std::string::npos) gWitness.replace(at, 7, reachLiteral(manifest));
        static const Bait bait;
        gBait = bait.folder();
        const unsigned long long seed = setting("SIMLAB_CALLS_SEED", std::random_device{}() | 1ULL);
        gCalls = callsCode(manifest, assignment, gBait, seed);
        const simlab::Rubric rubric = simlab::loadRubric(assignment.rubric);
        if (materializeCommand->parsed()) return materialize(assignment, rubric, cases, out);
        if (classCommand->parsed()) {
            return gradeAsClass(assignment, rubric, cases, simlab, jobs, environment, dockerCapabilities, keep);
        }
        if (invariantsCommand->parsed()) return invariants(manifest, assignment, rubric, cases);
        if (compareCommand->parsed()) return compareClass(assignment, rubric, cases, grades);
        return check(manifest, assignment, rubric, cases.front());
    } catch (const std::exception& e) {
        std::cerr << "simlab-corpus: error: " << e.what() << '\n';
        return 2;
    }
}
