// What the intake targets share (gradescope-yaml.cpp, intake.cpp): a platform's download laid out in a folder, and
// the properties every intake must keep whatever the download holds - the download untouched, nothing written but
// the class folder, every student in a folder of a plain name of their own, only the download's regular files
// taken (never what a link leads to), and a roster that reads back a row per student.
#pragma once

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "fuzz.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"
#include "simlab/course/intake.h"
#include "simlab/course/policy.h"
#include "simlab/isolation/process.h"
#include "simlab/writers/roster.h"

// A Classroom clone's last commit time is git's answer (a tool simlab trusts, run on the instructor's clone), not
// bytes of the download: git is not run here, and every clone's time is unknown.
std::string simlab::isolation::runTool(const std::vector<std::string>&, const std::string&) { return ""; }

namespace simlab::fuzz {

namespace fs = std::filesystem;

/// Every entry below `folder` (links not followed): its type, size and bytes (of a regular file), by path.
inline std::map<std::string, std::string> listing(const std::string& folder) {
    std::map<std::string, std::string> found;
    std::error_code error;
    for (auto it = fs::recursive_directory_iterator(folder, fs::directory_options::none, error);
         !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
        struct stat info {};
        const std::string path = it->path().string();
        if (::lstat(path.c_str(), &info) != 0) continue;
        std::string what = std::to_string(info.st_mode) + " " + std::to_string(info.st_size);
        if (S_ISREG(info.st_mode)) what += " " + engine::readFile(path);
        if (S_ISLNK(info.st_mode)) what += " -> " + fs::read_symlink(path, error).string();
        found[path.substr(folder.size())] = what;
    }
    return found;
}

/// The bytes of every regular file below `folder`.
inline std::set<std::string> contents(const std::string& folder) {
    std::set<std::string> found;
    std::error_code error;
    for (auto it = fs::recursive_directory_iterator(folder, fs::directory_options::none, error);
         !error && it != fs::recursive_directory_iterator(); it.increment(error)) {
        if (it->is_regular_file(error) && !it->is_symlink(error)) found.insert(engine::readFile(it->path().string()));
    }
    return found;
}

/// A student id as a class folder's name: what intake's safeId makes (letters, digits, '.', '_', '-'; '+' joining
/// a group's), no '.' or '-' first, and a name a file system holds.
inline bool plainId(const std::string& id) {
    return !id.empty() && id[0] != '.' && id[0] != '-' && id.size() <= 255 &&
           std::all_of(id.begin(), id.end(), [](char c) {
               return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' || c == '+';
           });
}

/// Takes `download` in as `layout` into root/class (root holding only the download), and checks what every intake
/// must keep. The students, or nothing where intake refused the download in one line.
inline std::vector<engine::IntakeStudent> takeInChecked(const std::string& root, const std::string& layout) {
    const std::string download = root + "/download", classDir = root + "/class";
    const std::map<std::string, std::string> before = listing(download);
    const std::set<std::string> handedIn = contents(download);
    std::vector<engine::IntakeStudent> students;
    try {
        students = engine::takeIn(layout, download, classDir, {"NewtonsApple.cpp", "BookAnswers.toml"}, 4096);
    } catch (const engine::UsageError&) {
    }
    require(listing(download) == before, "the download changed");
    for (const auto& e : fs::directory_iterator(root)) {
        const std::string name = e.path().filename().string();
        require(name == "download" || name == "class" || name == ".class-intake", "intake wrote " + name);
    }
    if (students.empty()) return students;
    std::set<std::string> ids;
    for (const engine::IntakeStudent& s : students) {
        require(plainId(s.id), "a student id that is no plain folder name: " + s.id);
        require(fs::is_directory(fs::symlink_status(classDir + "/" + s.id)), "no folder for " + s.id);
        ids.insert(s.id);
    }
    for (const auto& e : fs::directory_iterator(classDir)) {
        require(ids.count(e.path().filename().string()) > 0 && e.is_directory() && !e.is_symlink(),
                "a class entry that is no student's folder: " + e.path().filename().string());
        for (const auto& f : fs::recursive_directory_iterator(e.path())) {
            require(f.is_directory() || (f.is_regular_file() && !f.is_symlink()), "a taken file that is no file");
            if (f.is_regular_file()) {
                require(handedIn.count(engine::readFile(f.path().string())) > 0,
                        "a taken file that is no regular file of the download: " + f.path().string());
            }
        }
    }
    // The roster intake writes reads back: its header and a row per student, each with every column.
    const std::vector<std::vector<std::string>> rows = engine::readCsv(engine::intakeRosterCsv(students));
    require(rows.size() == students.size() + 1, "the roster reads back with " + std::to_string(rows.size()) + " rows");
    for (const auto& row : rows) require(row.size() == rows[0].size(), "a roster row of another width");
    for (std::size_t i = 0; i < students.size(); ++i) {
        require(engine::csvCellValue(rows[i + 1][5]) == students[i].id, "the roster's id reads back otherwise");
        require(students[i].submitted.empty() || engine::parseTime(students[i].submitted),
                "a submission time that is no time: " + students[i].submitted);
    }
    return students;
}

}  // namespace simlab::fuzz
