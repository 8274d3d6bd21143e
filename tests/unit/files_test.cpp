// A student's files are read as data: regular files only, never through a link, never blocking, never more than
// the limit.
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "simlab/common/files.h"

namespace files_test {

namespace fs = std::filesystem;
using simlab::engine::HandedIn;
using simlab::engine::readHandedIn;

namespace {

struct Folder {
    simlab::engine::TempDir dir{"simlab-files-test-"};
    std::string path(const std::string& name) const { return dir.path() + "/" + name; }
    void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
};

}  // namespace

TEST_CASE("a regular file is read whole", "[files]") {
    Folder f;
    f.write("A.cpp", "int x;\n");
    const HandedIn file = readHandedIn(f.dir.path(), "A.cpp", 1024, false);
    CHECK(file.found);
    CHECK(file.ok);
    CHECK(file.text == "int x;\n");
    const HandedIn missing = readHandedIn(f.dir.path(), "B.cpp", 1024, false);
    CHECK_FALSE(missing.found);
    CHECK_FALSE(missing.ok);
}

TEST_CASE("links, pipes and folders are refused without being followed or opened", "[files]") {
    Folder f;
    f.write("secret", "root:x:0:\n");
    fs::create_symlink(f.path("secret"), f.path("A.cpp"));
    REQUIRE(::mkfifo(f.path("P.cpp").c_str(), 0644) == 0);
    fs::create_directory(f.path("D.cpp"));
    const HandedIn link = readHandedIn(f.dir.path(), "A.cpp", 1024, false);
    CHECK(link.found);
    CHECK_FALSE(link.ok);
    CHECK(link.status == simlab::engine::SubmissionStatus::UnsafeFile);
    CHECK(link.refusal == "A.cpp is a symbolic link; hand in the file itself");
    CHECK(link.text.empty());
    // A pipe with no writer would block a reader forever.
    const auto start = std::chrono::steady_clock::now();
    const HandedIn pipe = readHandedIn(f.dir.path(), "P.cpp", 1024, false);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
    CHECK(pipe.refusal == "P.cpp is a named pipe; hand in the file itself");
    CHECK(readHandedIn(f.dir.path(), "D.cpp", 1024, false).refusal == "D.cpp is a folder; hand in the file itself");
}

TEST_CASE("a student's folder that is itself a link is not entered", "[files]") {
    Folder f;
    fs::create_directory(f.path("real"));
    f.write("real/A.cpp", "int x;\n");
    fs::create_symlink(f.path("real"), f.path("alias"));
    CHECK_FALSE(readHandedIn(f.path("alias"), "A.cpp", 1024, /*followFolder=*/false).ok);
    CHECK(readHandedIn(f.path("alias"), "A.cpp", 1024, /*followFolder=*/true).ok);  // a path the user named
}

TEST_CASE("a file over the limit is refused unread, however large it claims to be", "[files]") {
    Folder f;
    f.write("A.cpp", std::string(2048, 'x'));
    const HandedIn big = readHandedIn(f.dir.path(), "A.cpp", 1024, false);
    CHECK(big.status == simlab::engine::SubmissionStatus::FileTooLarge);
    CHECK(big.refusal == "A.cpp is 2 KiB; the limit is 1 KiB");
    // 3 GiB that take no room on disk.
    const int fd = ::open(f.path("S.cpp").c_str(), O_WRONLY | O_CREAT, 0644);
    REQUIRE(::ftruncate(fd, 3LL << 30) == 0);
    ::close(fd);
    CHECK(readHandedIn(f.dir.path(), "S.cpp", 1 << 20, false).refusal == "S.cpp is 3.0 GiB; the limit is 1.0 MiB");
}

TEST_CASE("a folder is listed and walked without following links", "[files]") {
    Folder f;
    fs::create_directories(f.path("sub/deeper"));
    f.write("sub/deeper/A.cpp", "");
    fs::create_symlink("/", f.path("root"));
    const auto entries = simlab::engine::walkFolder(f.dir.path());
    std::vector<std::string> names;
    for (const auto& e : entries) names.push_back(e.name);
    CHECK(names == std::vector<std::string>{"root", "sub", "sub/deeper", "sub/deeper/A.cpp"});
    CHECK(entries[0].type == simlab::engine::EntryType::Symlink);
}

TEST_CASE("an output is written as the umask gives it, and written again keeps the mode it was given", "[files]") {
    simlab::engine::TempDir dir("simlab-output-test-");
    const std::string sheet = dir.path() + "/manual.csv", judge = dir.path() + "/judge.txt";
    const mode_t before = ::umask(002);
    simlab::engine::writeOutputAtomically(sheet, "a\n");
    simlab::engine::writeFileAtomically(judge, "a\n");
    ::umask(022);  // sudo's, on the next run
    struct stat info {};
    REQUIRE(::stat(sheet.c_str(), &info) == 0);
    CHECK((info.st_mode & 0777) == 0664);  // the staff's group may edit it
    simlab::engine::writeOutputDurably(sheet, "b\n");
    REQUIRE(::stat(sheet.c_str(), &info) == 0);
    CHECK((info.st_mode & 0777) == 0664);  // still, whatever the umask now
    simlab::engine::writeOutputAtomically(dir.path() + "/report.html", "c\n");
    REQUIRE(::stat((dir.path() + "/report.html").c_str(), &info) == 0);
    CHECK((info.st_mode & 0777) == 0644);  // a new one as this umask gives it
    REQUIRE(::stat(judge.c_str(), &info) == 0);
    CHECK((info.st_mode & 0777) == 0644);  // a file of simlab's own: 0644 whatever the umask
    ::umask(before);
}

}  // namespace files_test
