// The builder's defenses: a cached object is used only for the very file it was compiled from, and the sandbox's
// system-call filter refuses what would let one student's code reach another's while threads still work.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "simlab/build/build.h"
#include "simlab/common/files.h"
#include "simlab/build/manifest.h"
#include "simlab/isolation/process.h"

namespace build_test {

using namespace simlab::engine;
using namespace simlab::isolation;
namespace fs = std::filesystem;

TEST_CASE("keys are SHA-256 of their fields, each field kept apart", "[build]") {
    CHECK(Hash().add("ab").add("c").hex() != Hash().add("a").add("bc").hex());
    CHECK(Hash().add("abc").hex() == Hash().add("abc").hex());
    CHECK(Hash().add("abc").hex().size() == 64);
    Hash h;
    h.add("x");
    Hash copy = h;
    CHECK(copy.add("y").hex() == Hash().add("x").add("y").hex());
    CHECK(h.hex() == Hash().add("x").hex());  // the copy went on alone
}

TEST_CASE("a cached object is used only for the file it was compiled from", "[build]") {
    // A planted object under this file's key, whose recorded source is another file's: the file is compiled anew
    // rather than graded as the other.
    TempDir cache("simlab-cache-test-");
    ::setenv("SIMLAB_CACHE", cache.path().c_str(), 1);
    const Manifest manifest = loadManifest();
    const Assignment& apple = manifest.find("apple");
    const Builder builder(manifest);
    ::unsetenv("SIMLAB_CACHE");
    const std::string text = readFile(apple.solution);
    const std::string key = builder.objectKey(apple, "NewtonsApple.cpp", text);
    // The same bytes under another name are another object: the name is in its messages and its __FILE__.
    CHECK(builder.objectKey(apple, "Other.cpp", text) != key);
    CHECK(builder.cacheDir() == cache.path() + "/objects");  // $SIMLAB_CACHE holds every cache
    writeFileAtomically(builder.cacheDir() + "/" + key + ".o", "not an object");
    writeFileAtomically(builder.cacheDir() + "/" + key + ".cpp", readFile(apple.starter));
    TempDir work("simlab-build-test-");
    fs::create_directory(work.path() + "/build");
    fs::create_directory(work.path() + "/probe");
    const BuildResult built = builder.buildProbe(apple, "NewtonsApple.cpp", text, work.path() + "/build",
                                                 work.path() + "/probe/probe");
    CHECK_FALSE(built.cached);
    CHECK(built.ok);
    CHECK(readFile(builder.cacheDir() + "/" + key + ".cpp") == text);
}

TEST_CASE("the sandbox refuses the kernel keyring and new namespaces, and lets threads start", "[build][sandbox]") {
    if (!sandboxSupport().bubblewrap) return;  // nothing to test without bubblewrap
    TempDir dir("simlab-seccomp-test-");
    writeFileAtomically(dir.path() + "/probe.cpp", R"(
        #include <sched.h>
        #include <sys/syscall.h>
        #include <unistd.h>
        #include <cerrno>
        #include <cstdio>
        #include <thread>
        int main() {
            const long key = syscall(SYS_add_key, "user", "simlab-note", "x", 1, -4);
            std::printf("add_key %s\n", key < 0 && errno == EPERM ? "refused" : "allowed");
            std::printf("unshare %s\n", unshare(CLONE_NEWUSER) != 0 && errno == EPERM ? "refused" : "allowed");
            int seen = 0;
            std::thread([&] { seen = 1; }).join();
            std::printf("thread %s\n", seen == 1 ? "ran" : "did not run");
        })");
    REQUIRE(std::system(("/usr/bin/g++ -std=c++17 -pthread " + dir.path() + "/probe.cpp -o " + dir.path() + "/probe").c_str()) == 0);
    fs::permissions(dir.path(), fs::perms::all & ~fs::perms::group_write & ~fs::perms::others_write);
    ProcessRequest r;
    r.argv = {dir.path() + "/probe"};
    r.env = {"PATH=/usr/bin:/bin"};
    r.workDir = dir.path() + "/work";
    fs::create_directory(r.workDir);
    r.isolate = true;
    r.scratchWorkDir = true;
    r.readOnlyPaths = {dir.path() + "/probe"};
    const ProcessResult result = runProcess(r);
    INFO(result.output << result.error);
    CHECK(result.exitCode == 0);
    CHECK(result.output == "add_key refused\nunshare refused\nthread ran\n");
}

}  // namespace build_test
