// sandbox-check: runs sandbox-try in simlab's sandbox, as a test's probe is run, and checks each rule of the mode
// this machine gives (bubblewrap, Landlock or limits only; SIMLAB_NO_BUBBLEWRAP=1 and SIMLAB_NO_LANDLOCK=1 choose
// the fallbacks): every filtered call refused, a session of its own with no terminal, no network, no file outside
// what it is lent (or, with limits only, simlab's audit names it), nothing left in the shared temporary folders,
// no process left behind, memory counted over all its processes. Prints one line per check; exit 1 if any fails.
//
//   sandbox-check SANDBOX-TRY
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/common/files.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;
using namespace simlab::engine;
using namespace simlab::isolation;

namespace {

int failures = 0;

void check(const std::string& what, bool ok, const std::string& detail = "") {
    std::cout << (ok ? "ok: " : "FAIL: ") << what << (detail.empty() ? "" : " (" + detail + ")") << "\n";
    if (!ok) ++failures;
}

// sandbox-try's lines, "name: result", by name.
std::map<std::string, std::string> resultsOf(const std::string& output) {
    std::map<std::string, std::string> results;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t colon = line.find(": ");
        if (colon != std::string::npos) results[line.substr(0, colon)] = line.substr(colon + 2);
        else if (!line.empty() && line.back() == ':') results[line.substr(0, line.size() - 1)] = "";
    }
    return results;
}

// Processes named `name` (their comm) anywhere on the machine.
int processesNamed(const std::string& name) {
    int count = 0;
    if (DIR* proc = ::opendir("/proc")) {
        while (const struct dirent* entry = ::readdir(proc)) {
            std::ifstream comm(std::string("/proc/") + entry->d_name + "/comm");
            std::string line;
            if (std::getline(comm, line) && line == name) {
                std::ifstream stat(std::string("/proc/") + entry->d_name + "/stat");
                std::string all;
                std::getline(stat, all);
                const std::size_t close = all.rfind(')');
                if (close != std::string::npos && close + 2 < all.size() && all[close + 2] != 'Z') ++count;
            }
        }
        ::closedir(proc);
    }
    return count;
}

int leftInTmp() {
    int count = 0;
    for (const char* dir : {"/tmp", "/var/tmp", "/dev/shm"}) {
        std::error_code error;
        for (auto it = fs::directory_iterator(dir, error); !error && it != fs::directory_iterator(); it.increment(error)) {
            if (it->path().filename().string().rfind("simlab-sandbox-try-", 0) == 0) ++count;
        }
    }
    return count;
}

ProcessResult runTry(const std::string& program, const std::vector<std::string>& actions, const TempDir& lent,
                     double memoryMiB = 1024) {
    TempDir work("simlab-sandbox-work-");
    ProcessRequest r;
    r.argv = {program};
    r.argv.insert(r.argv.end(), actions.begin(), actions.end());
    r.env = childEnvironment();
    r.workDir = work.path();
    r.isolate = true;
    r.scratchWorkDir = true;
    r.readOnlyPaths = {lent.path()};
    r.limits.cpuSeconds = 20;
    r.limits.wallSeconds = 120;
    r.limits.memoryMiB = memoryMiB;
    r.limits.processes = 32;
    r.keepOutput = 1 << 20;
    return runProcess(r);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: sandbox-check SANDBOX-TRY\n";
        return 2;
    }
    const SandboxSupport& support = sandboxSupport();
    std::cout << "sandbox: " << support.summary << "\n";
    if (!support.warning.empty()) std::cout << "warning: " << support.warning << "\n";
    const bool root = ::geteuid() == 0;

    // The program, lent to the sandbox as a probe's is; a secret beside nothing it is lent.
    TempDir lent("simlab-sandbox-lent-");
    const std::string program = lent.path() + "/sandbox-try";
    fs::copy_file(argv[1], program);
    fs::permissions(lent.path(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                     fs::perms::others_read | fs::perms::others_exec);
    TempDir secretDir("simlab-sandbox-secret-");
    const std::string secret = secretDir.path() + "/hidden-tests.cpp";
    writeFileAtomically(secret, "TEST_CASE(\"a hidden test\") {}\n");
    fs::permissions(secretDir.path(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                          fs::perms::others_read | fs::perms::others_exec);
    fs::permissions(secret, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                                fs::perms::others_read);

    const ProcessResult run = runTry(program, {"calls", "thread", "session", "tty", "read:" + secret, "write:/tmp",
                                               "connect:22", "signal:" + std::to_string(::getpid()), "daemon"},
                                     lent);
    check("sandbox-try ran and finished", run.started && run.exitCode == 0,
          run.started && run.exitCode == 0 ? "" : run.error + run.output.substr(0, 300));
    const std::map<std::string, std::string> results = resultsOf(run.output);
    auto result = [&](const std::string& name) {
        const auto found = results.find(name);
        return found == results.end() ? std::string("(no answer)") : found->second;
    };
    int calls = 0;
    for (const auto& [name, what] : results) {
        if (name.rfind("call ", 0) != 0) continue;
        ++calls;
        check("the filter refuses " + name.substr(5), what == "refused", what);
    }
    check("every filtered call was tried (" + std::to_string(calls) + ")", calls >= 40);
    check("threads start", result("thread") == "ran", result("thread"));
    // Without bubblewrap the process simlab starts leads a new session; bubblewrap starts it in a new session of
    // its own making (--new-session) inside its process namespace, led by bubblewrap's first process.
    if (!support.bubblewrap) check("a session of its own", result("session") == "its own", result("session"));
    check("no terminal: /dev/tty cannot be opened", result("open /dev/tty").rfind("refused", 0) == 0,
          result("open /dev/tty"));
    check("no network: a connection to 127.0.0.1 is refused", result("connect 22") == "refused", result("connect 22"));
    if (root) {
        check("simlab's own process cannot be signalled", result("signal " + std::to_string(::getpid())) == "refused",
              result("signal " + std::to_string(::getpid())));
    }
    const std::string read = result("read " + secret);
    addPlaces({secretDir.path()});
    const Exposure audit = exposedPlaces({});
    if (support.bubblewrap || support.landlock) {
        check("a file it is not lent cannot be read", read == "unreadable", read);
        check(support.bubblewrap ? "/tmp is its own" : "/tmp cannot be written",
              support.bubblewrap || result("write /tmp") == "unwritable", result("write /tmp"));
    } else {
        // Limits only: permissions alone keep files apart, so simlab's audit must name what a test could read.
        check("with limits only, the audit names a file readable by all (" + read + ")",
              std::find(audit.readable.begin(), audit.readable.end(), secret) != audit.readable.end());
    }
    check("nothing it wrote is left in the shared temporary folders", leftInTmp() == 0,
          std::to_string(leftInTmp()) + " left");
    check("no process is left behind (the daemon that left its tree is ended)", processesNamed("sbx-daemon") == 0,
          std::to_string(processesNamed("sbx-daemon")) + " left");
    check("no process of its user was left to end", run.leftBehind == 0, std::to_string(run.leftBehind));

    // Memory is the test's, over all its processes: four of 100 MiB each under a limit of 256 MiB.
    const ProcessResult memory = runTry(program, {"memory:4:100"}, lent, 256);
    check("four processes of 100 MiB each under a 256 MiB limit: killed for memory, together",
          memory.memoryLimit && !memory.cpuTimeout, "status " + std::to_string(memory.exitCode) + ", signal " +
          std::to_string(memory.signal) + ", peak " + std::to_string(memory.maxRssKiB / 1024) + " MiB");
    const ProcessResult small = runTry(program, {"memory:2:50"}, lent, 256);
    check("and two of 50 MiB are not (the limit is not too tight to pass)", !small.memoryLimit,
          "peak " + std::to_string(small.maxRssKiB / 1024) + " MiB");

    // Its folder's space: many files, each under the file-size limit (16 MiB). bubblewrap's folder is a memory file
    // system of that size; elsewhere the folder is on a disk, and simlab stops the test once its files take three
    // times the limit (what bubblewrap's three memory folders give).
    const ProcessResult disk = runTry(program, {"disk:16"}, lent);
    const std::string wrote = resultsOf(disk.output)["disk"];
    const long mib = wrote.rfind("wrote ", 0) == 0 ? std::atol(wrote.c_str() + 6) : -1;
    check("files past the space a test has: refused (a full folder) or stopped, never 1 GiB",
          disk.diskLimit || (mib >= 0 && mib <= 48), wrote + (disk.diskLimit ? ", stopped" : ""));
    // The same in /tmp: bubblewrap's is a memory file system of its own, Landlock lets nothing be written there,
    // and with limits only what the test's user writes in the machine's shared temporary folders counts as its own.
    const ProcessResult tmpDisk = runTry(program, {"disk:16:/tmp"}, lent);
    const std::string wroteTmp = resultsOf(tmpDisk.output)["disk"];
    const long tmpMib = wroteTmp.rfind("wrote ", 0) == 0 ? std::atol(wroteTmp.c_str() + 6) : -1;
    check("files past the space a test has, in /tmp: refused or stopped, never 1 GiB",
          tmpDisk.diskLimit || (tmpMib >= 0 && tmpMib <= 48), wroteTmp + (tmpDisk.diskLimit ? ", stopped" : ""));

    // A call of the x32 ABI, which a filter for x86-64 alone would miss: the process is ended or the call refused.
    const ProcessResult x32 = runTry(program, {"x32"}, lent);
    const std::string x32Result = resultsOf(x32.output)["x32"];
    check("an x32 system call is refused or ends the process", x32.signal == SIGSYS || x32Result == "refused",
          "signal " + std::to_string(x32.signal) + ", " + x32Result);

    std::cout << (failures == 0 ? "all checks passed\n" : std::to_string(failures) + " check(s) failed\n");
    return failures == 0 ? 0 : 1;
}
