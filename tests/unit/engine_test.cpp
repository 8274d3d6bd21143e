// The engine's process runner: every way a child can end is told apart, and only the report channel counts.
#include <catch2/catch.hpp>
#include <csignal>
#include <fcntl.h>
#include <unistd.h>
#include <string>

#include "simlab/isolation/process.h"

namespace engine_test {

using simlab::isolation::ProcessRequest;
using simlab::isolation::ProcessResult;
using simlab::isolation::runProcess;

namespace {

ProcessResult shell(const std::string& script, double wallSeconds = 5, bool channel = false) {
    ProcessRequest r;
    r.argv = {"/bin/sh", "-c", script};
    r.env = simlab::isolation::childEnvironment();
    r.workDir = ".";
    r.limits.wallSeconds = wallSeconds;
    r.limits.cpuSeconds = wallSeconds;
    r.reportChannel = channel;
    return runProcess(r);
}

}  // namespace

TEST_CASE("a child that exits is reported with its status and output", "[process]") {
    const ProcessResult ok = shell("echo hello; echo oops >&2; exit 3");
    CHECK(ok.started);
    CHECK(ok.exitCode == 3);
    CHECK(ok.signal == 0);
    CHECK(ok.output == "hello\noops\n");
    CHECK_FALSE(ok.wallTimeout);
}

TEST_CASE("a child that runs past the wall-clock limit is killed with everything it started", "[process]") {
    const ProcessResult slow = shell("sleep 30 & sleep 30", 0.5);
    CHECK(slow.wallTimeout);
    CHECK(slow.signal == SIGKILL);
    CHECK(slow.wallSeconds < 5);  // not the 30 s the sleeps asked for
}

TEST_CASE("a child that spins is stopped by the CPU limit", "[process]") {
    ProcessRequest r;
    r.argv = {"/bin/sh", "-c", "while :; do :; done"};
    r.env = simlab::isolation::childEnvironment();
    r.workDir = ".";
    r.limits.cpuSeconds = 1;
    r.limits.wallSeconds = 10;
    const ProcessResult spin = runProcess(r);
    CHECK(spin.cpuTimeout);
    CHECK_FALSE(spin.wallTimeout);
}

TEST_CASE("a crash is reported with its signal's name", "[process]") {
    const ProcessResult crash = shell("kill -SEGV $$");
    CHECK(crash.signal == SIGSEGV);
    CHECK(simlab::isolation::signalName(crash.signal) == "SIGSEGV");
}

TEST_CASE("a child that floods its output is stopped at the limit", "[process]") {
    ProcessRequest r;
    r.argv = {"/bin/sh", "-c", "yes flood"};
    r.env = simlab::isolation::childEnvironment();
    r.workDir = ".";
    r.limits.outputKiB = 64;
    const ProcessResult flood = runProcess(r);
    CHECK(flood.outputLimit);
    CHECK(flood.output.size() <= r.keepOutput);
    CHECK(flood.outputBytes > 64 * 1024);
}

TEST_CASE("the report channel carries complete lines; a line cut short is not a report", "[process]") {
    const ProcessResult r = shell("echo 'not a report'; echo '{\"event\":\"end\"}' >&3; printf 'cut' >&3", 5,
                                  /*channel=*/true);
    REQUIRE(r.reports.size() == 1);
    CHECK(r.reports[0] == "{\"event\":\"end\"}");
}

TEST_CASE("descriptors handed to a child arrive where asked, and simlab keeps no copy", "[process]") {
    int pipe[2];
    REQUIRE(::pipe2(pipe, O_CLOEXEC) == 0);
    ProcessRequest r;
    r.argv = {"/bin/sh", "-c", "echo through >&5"};
    r.env = simlab::isolation::childEnvironment();
    r.workDir = ".";
    r.passFds = {{5, pipe[1]}};
    const ProcessResult result = runProcess(r);
    CHECK(result.exitCode == 0);
    CHECK(::fcntl(pipe[1], F_GETFD) == -1);  // closed in simlab once the child had it
    char text[16] = {0};
    CHECK(::read(pipe[0], text, sizeof text - 1) == 8);
    CHECK(std::string(text) == "through\n");
    ::close(pipe[0]);
}

TEST_CASE("a child sees none of simlab's other file descriptors", "[process]") {
    // Opened without close-on-exec, as a terminal or a CI runner's pipe would be inherited.
    const int opened = ::open("/dev/null", O_RDONLY);
    const int leaked = ::fcntl(opened, F_DUPFD, 50);
    ::close(opened);
    REQUIRE(leaked >= 50);
    const ProcessResult r = shell("for f in /proc/$$/fd/*; do echo ${f##*/}; done", 5, /*channel=*/true);
    ::close(leaked);
    // stdin, stdout, stderr, the report pipe (and the directory the shell's glob is reading).
    CHECK(r.output.rfind("0\n1\n2\n3\n", 0) == 0);
    CHECK(r.output.find("\n" + std::to_string(leaked) + "\n") == std::string::npos);
}

TEST_CASE("a program that cannot be executed is reported, not run", "[process]") {
    ProcessRequest r;
    r.argv = {"/nonexistent/program"};
    r.workDir = ".";
    const ProcessResult result = runProcess(r);
    CHECK_FALSE(result.started);
    CHECK(result.error == "simlab: cannot execute the program: No such file or directory");
}

}  // namespace engine_test
