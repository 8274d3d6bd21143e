// simlab/system_tool.h: the one way a lab program runs a tool of the system (dot, gnuplot).
#include <catch2/catch.hpp>

#include <string>

#include "simlab/system_tool.h"

namespace system_tool_test {

TEST_CASE("a system tool reads its input and its output comes back", "[system_tool]") {
    const simlab::SystemToolRun run = simlab::runSystemTool({"cat"}, "a line\nand another\n", 10, 1 << 20);
    CHECK(run.succeeded());
    CHECK(run.output == "a line\nand another\n");
    CHECK(run.errors.empty());
}

TEST_CASE("more than a pipe's buffer each way goes through without a deadlock", "[system_tool]") {
    const std::string big(1 << 20, 'x');  // 1 MiB in, the same out
    const simlab::SystemToolRun run = simlab::runSystemTool({"cat"}, big, 10, 2 << 20);
    CHECK(run.output.size() == big.size());
}

TEST_CASE("a tool's failure is its first line of complaint, or how it ended", "[system_tool]") {
    const simlab::SystemToolRun said =
        simlab::runSystemTool({"sh", "-c", "echo '  the reason' >&2; exit 3"}, "", 10, 1024);
    CHECK(!said.succeeded());
    CHECK(said.reason() == "the reason");
    const simlab::SystemToolRun silent = simlab::runSystemTool({"sh", "-c", "exit 4"}, "", 10, 1024);
    CHECK(silent.reason() == "exit status 4");
    const simlab::SystemToolRun killed = simlab::runSystemTool({"sh", "-c", "kill -9 $$"}, "", 10, 1024);
    CHECK(!killed.exited);
    CHECK(killed.reason() == "killed by signal 9");
}

TEST_CASE("a missing tool, a flood and a tool that does not end are errors, each said", "[system_tool]") {
    CHECK_THROWS_AS(simlab::runSystemTool({"simlab-no-such-tool"}, "", 10, 1024), simlab::SystemToolMissing);
    CHECK_THROWS_WITH(simlab::runSystemTool({"yes"}, "", 10, 1 << 20),
                      Catch::Matchers::StartsWith("yes failed: its output is larger than 1 MiB"));
    CHECK_THROWS_WITH(simlab::runSystemTool({"sleep", "30"}, "", 1, 1024),
                      Catch::Matchers::StartsWith("sleep failed: it took longer than 1 s"));
}

TEST_CASE("a tool that stops reading its input does not end the program (SIGPIPE)", "[system_tool]") {
    const simlab::SystemToolRun run = simlab::runSystemTool({"head", "-c", "1"}, std::string(4 << 20, 'y'), 10, 1024);
    CHECK(run.succeeded());
    CHECK(run.output == "y");
}

}  // namespace system_tool_test
