// What a test may read (isolation/reach.h): the declaration, the audit of limits only, simlab lock, and the folders
// a stopped run leaves behind.
#include <catch2/catch.hpp>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fcntl.h>
#include <filesystem>
#include <fstream>

#include "simlab/build/lock.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/isolation/reach.h"

namespace reach_test {

namespace fs = std::filesystem;
using namespace simlab::isolation;

namespace {

void write(const std::string& path, mode_t mode) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream(path) << "text\n";
    fs::permissions(path, static_cast<fs::perms>(mode));
}

mode_t modeOf(const std::string& path) {
    struct stat info {};
    REQUIRE(::lstat(path.c_str(), &info) == 0);
    return info.st_mode & 07777;
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
    return std::find(list.begin(), list.end(), item) != list.end();
}

}  // namespace

TEST_CASE("the system's folders are never a place, and a place is out of reach but what is lent", "[reach]") {
    simlab::engine::TempDir dir("simlab-reach-test-");
    const std::string place = dir.path() + "/course";
    addPlaces({"/", "/usr", "/", place});
    const std::vector<std::string> all = places();
    CHECK_FALSE(contains(all, "/"));
    CHECK_FALSE(contains(all, "/usr"));
    CHECK(contains(all, place));
    CHECK(placeOf(place + "/build/judge") == place);
    CHECK(placeOf(dir.path() + "/coursework") == "");  // a name that starts alike is not inside
    // The system, less the places; what is lent, and the process's own folder, wherever they lie.
    CHECK(withinReach("/usr/lib/x86_64-linux-gnu/libc.so.6", {}, ""));
    CHECK(withinReach("/etc/ld.so.cache", {}, ""));
    CHECK_FALSE(withinReach("/etc/shadow", {}, ""));
    CHECK_FALSE(withinReach("/home/ta/grades.csv", {}, ""));
    CHECK_FALSE(withinReach(place + "/grading/hidden.cpp", {}, ""));
    CHECK(withinReach(place + "/contract/Apple.h", {place + "/contract"}, ""));
    CHECK_FALSE(withinReach(place + "/contractual.h", {place + "/contract"}, ""));
    CHECK(withinReach("/tmp/work/j1-test3/out.txt", {}, "/tmp/work/j1-test3"));
    CHECK_FALSE(withinReach("/tmp/work/j1-judge/rubric.toml", {}, "/tmp/work/j1-test3"));
    CHECK(visibleInSandboxes("/usr/bin"));
    CHECK_FALSE(visibleInSandboxes(place));
    // /usr/local is the machine's own, not the system's: another course's lab there is no test's to read.
    CHECK_FALSE(withinReach("/usr/local/share/labs/pendulum/.git/objects/96/1492f3", {}, ""));
    CHECK_FALSE(visibleInSandboxes("/usr/local/lib"));
    CHECK(withinReach("/usr/local/lib/libSimTKsimbody.so.3.7", {"/usr/local/lib/libSimTKsimbody.so.3.7"}, ""));
}

TEST_CASE("limits only: every file of the places that opens for a throwaway user, but what is lent", "[reach]") {
    simlab::engine::TempDir dir("simlab-reach-test-");
    fs::permissions(dir.path(), fs::perms::owner_all | fs::perms::others_exec | fs::perms::others_read);
    const std::string place = dir.path() + "/lab";
    write(place + "/.git/objects/96/1492f3", 0444);  // as git makes them
    write(place + "/solution/Lab.cpp", 0600);
    write(place + "/contract/Lab.h", 0644);
    fs::permissions(place, fs::perms::owner_all | fs::perms::others_exec | fs::perms::others_read);
    for (const std::string& d : {place + "/.git", place + "/.git/objects", place + "/.git/objects/96", place + "/contract"}) {
        fs::permissions(d, fs::perms::owner_all | fs::perms::others_exec | fs::perms::others_read);
    }
    addPlaces({place});
    const Exposure exposure = exposedPlaces({place + "/contract"});
    REQUIRE(exposure.error.empty());
    if (::geteuid() == 0) {
        // A throwaway user opens what others may read - the history git made 0444 - and nothing closed or lent.
        CHECK(contains(exposure.readable, place + "/.git/objects/96/1492f3"));
        CHECK_FALSE(contains(exposure.readable, place + "/solution/Lab.cpp"));
    } else {
        // Not as root, a test runs as this user: it opens this user's own files too.
        CHECK(contains(exposure.readable, place + "/solution/Lab.cpp"));
    }
    CHECK_FALSE(contains(exposure.readable, place + "/contract/Lab.h"));
    CHECK(exposure.exposed());
}

TEST_CASE("limits only: below a folder others may not pass through nothing is tried, however much it holds",
          "[reach]") {
    // As root alone a test runs as a user with no group, whom a folder's modes keep out.
    if (::geteuid() != 0) return;
    simlab::engine::TempDir dir("simlab-reach-test-");
    fs::permissions(dir.path(), fs::perms::owner_all | fs::perms::others_exec | fs::perms::others_read);
    const std::string place = dir.path() + "/class";
    // A student's folder, closed as simlab lock closes it, that holds many files others could read were it open;
    // and one left open.
    for (int i = 0; i < 50; ++i) write(place + "/bob/junk/" + std::to_string(i), 0644);
    write(place + "/ann/NewtonsApple.cpp", 0644);
    fs::permissions(place, fs::perms::owner_all | fs::perms::others_exec);
    fs::permissions(place + "/bob", fs::perms::owner_all);
    fs::permissions(place + "/bob/junk", fs::perms::owner_all | fs::perms::others_exec | fs::perms::others_read);
    fs::permissions(place + "/ann", fs::perms::owner_all | fs::perms::others_exec | fs::perms::others_read);
    addPlaces({place});
    // This folder's files alone: the process's other places (the build and the sources, where the suite's other
    // tests write as this one runs) lent, so that the counts below are this folder's. Not a place that holds it.
    const std::string here = fs::canonical(dir.path()).string();
    auto isHere = [&](const std::string& p) {
        for (const std::string& d : {dir.path(), here}) {
            if (p == d || p.rfind(d + "/", 0) == 0 || d.rfind(p + "/", 0) == 0) return true;
        }
        return false;
    };
    std::vector<std::string> others;
    for (const std::string& p : places()) {
        if (!isHere(p)) others.push_back(p);
    }
    const Exposure exposure = exposedPlaces(others);
    REQUIRE(exposure.error.empty());
    CHECK(contains(exposure.readable, place + "/ann/NewtonsApple.cpp"));
    CHECK_FALSE(std::any_of(exposure.readable.begin(), exposure.readable.end(),
                            [&](const std::string& f) { return f.rfind(place + "/bob/", 0) == 0; }));
    // The files under the closed folder are not walked: what is tried is what others may reach. Opened, the
    // folder's 50 files are tried, and read.
    CHECK_FALSE(exposure.bounded);
    fs::permissions(place + "/bob", fs::perms::owner_all | fs::perms::others_exec);
    const Exposure open = exposedPlaces(others);
    CHECK(open.tried == exposure.tried + 50);
    CHECK(open.readableCount == exposure.readableCount + 50);
}

TEST_CASE("simlab lock closes the places to others but what is lent, and leaves the group's modes", "[reach]") {
    simlab::engine::TempDir dir("simlab-reach-test-");
    const std::string source = dir.path() + "/simlab", build = source + "/build";
    write(source + "/assignments/lab/grading/hidden.cpp", 0664);
    write(build + "/ccache/e/d/result.R", 0644);
    write(build + "/contract/lab/Lab.h", 0640);
    write(build + "/bin/simlab-probe-host", 0750);
    write(build + "/grader/probe.o", 0640);
    simlab::engine::Manifest manifest;
    manifest.path = build + "/simlab-build.json";
    manifest.sourceDir = source;
    manifest.buildDir = build;
    manifest.cacheDir = build + "/cache";
    manifest.probeHost = build + "/bin/simlab-probe-host";
    simlab::engine::Assignment lab;
    lab.id = "lab";
    lab.dir = source + "/assignments/lab";
    lab.contractInclude = build + "/contract/lab";
    lab.probeObjects = {build + "/grader/probe.o"};
    manifest.assignments.push_back(lab);
    const simlab::engine::LockSummary summary = simlab::engine::lockPlaces(manifest, {});
    CHECK(summary.closed > 0);
    CHECK(modeOf(source + "/assignments/lab/grading/hidden.cpp") == 0660);  // the group keeps its reach
    CHECK(modeOf(build + "/ccache/e/d/result.R") == 0640);
    CHECK(modeOf(build + "/ccache") == (modeOf(build + "/ccache") & ~07));
    CHECK(modeOf(build + "/contract/lab/Lab.h") == 0644);  // lent: others read it
    CHECK((modeOf(build + "/contract/lab") & 07) == 05);
    CHECK(modeOf(build + "/bin/simlab-probe-host") == 0755);  // a program lent: others run it
    CHECK(modeOf(build + "/grader/probe.o") == 0644);
    CHECK((modeOf(build) & 07) == 01);  // on the way to what is lent: passable, not listable
    CHECK((modeOf(source) & 07) == 01);
    CHECK((modeOf(source + "/assignments") & 07) == 0);
}

TEST_CASE("a folder a stopped run left behind is swept, one a live run holds is kept", "[reach]") {
    simlab::engine::TempDir base("simlab-reach-test-");
    // Left behind: a run's folder and its hold, which nobody keeps locked.
    const std::string left = base.path() + "/simlab-apple-AbC123";
    fs::create_directories(left + "/j1-server");
    write(left + "/j1-server/probe.so", 0600);
    std::ofstream(left + ".held").close();
    // Live: a folder of a running simlab (this process).
    simlab::engine::TempDir live("simlab-apple-", base.path());
    const std::vector<std::string> removed = simlab::engine::sweepLeftovers({base.path()});
    CHECK(contains(removed, "simlab-apple-AbC123"));
    CHECK_FALSE(fs::exists(left));
    CHECK_FALSE(fs::exists(left + ".held"));
    CHECK(fs::is_directory(live.path()));
    CHECK(fs::exists(live.path() + ".held"));
}

}  // namespace reach_test
