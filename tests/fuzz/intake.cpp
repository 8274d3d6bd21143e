// A platform's download taken in (course/intake.cpp): the names and folders of Canvas's, Moodle's and GitHub
// Classroom's downloads are the students' (a file's name, a display name, a repository's folder) and may hold any
// byte a file name can, links and pipes included. The download is laid out from the input, then taken in as the
// platform it names, or as the platform simlab tells from its layout.
//
// An input is the platform on its first line (canvas, moodle, classroom, gradescope, or auto), then an entry a
// line, its kind, a space, and its path in the download ('/' between folders; no "." or ".." part):
//     f PATH            a regular file (its bytes name it)
//     F PATH<TAB>TEXT   a regular file of that text
//     d PATH            a folder
//     l PATH<TAB>TARGET a symbolic link (never followed here)
//     p PATH            a named pipe
//     g PATH            a git repository's folder (PATH/.git)
//     t PATH<TAB>SECS   PATH's modification time, in seconds since 1970
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>

#include "download.h"

namespace {

namespace fs = std::filesystem;

// `path` as a relative path of plain parts, or empty.
std::string safePath(const std::string& path) {
    if (path.empty() || path.size() > 1024 || path[0] == '/' || path.find('\0') != std::string::npos) return "";
    std::size_t at = 0;
    while (at <= path.size()) {
        const std::size_t slash = std::min(path.find('/', at), path.size());
        const std::string part = path.substr(at, slash - at);
        if (part.empty() || part == "." || part == ".." || part.size() > 200) return "";
        at = slash + 1;
    }
    return path;
}

void layOut(const std::string& download, const std::vector<std::string>& lines) {
    std::error_code error;
    int made = 0;
    for (const std::string& line : lines) {
        if (line.size() < 3 || line[1] != ' ' || ++made > 64) continue;
        const std::string rest = line.substr(2);
        const std::size_t tab = rest.find('\t');
        const std::string path = safePath(rest.substr(0, tab));
        const std::string extra = tab == std::string::npos ? "" : rest.substr(tab + 1);
        if (path.empty()) continue;
        const std::string full = download + "/" + path;
        fs::create_directories(fs::path(full).parent_path(), error);
        switch (line[0]) {
            case 'f': ::close(::open(full.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
                      if (fs::is_regular_file(fs::symlink_status(full, error))) simlab::fuzz::write(full, "// " + path + "\n");
                      break;
            case 'F': ::close(::open(full.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644));
                      if (fs::is_regular_file(fs::symlink_status(full, error))) simlab::fuzz::write(full, extra);
                      break;
            case 'd': fs::create_directories(full, error); break;
            case 'g': fs::create_directories(full + "/.git", error); break;
            case 'l': ::symlink(extra.c_str(), full.c_str()); break;
            case 'p': ::mkfifo(full.c_str(), 0644); break;
            case 't': {
                const struct timespec times[2] = {{std::atoll(extra.c_str()), 0}, {std::atoll(extra.c_str()), 0}};
                ::utimensat(AT_FDCWD, full.c_str(), times, AT_SYMLINK_NOFOLLOW);
                break;
            }
            default: break;
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab;
    std::vector<std::string> lines = fuzz::parts(fuzz::text(data, size), "\n", 80);
    const std::string& root = fuzz::scratch().fresh();
    fs::create_directories(root + "/download");
    layOut(root + "/download", std::vector<std::string>(lines.begin() + 1, lines.end()));
    const std::string layout = engine::layoutOf(root + "/download");
    const std::string platform = lines[0] == "auto" ? layout : lines[0];
    const std::vector<std::string>& known = engine::downloadLayouts();
    if (std::find(known.begin(), known.end(), platform) == known.end()) return 0;
    const std::vector<engine::IntakeStudent> students = fuzz::takeInChecked(root, platform);
    // Ids are the platform's: two of its students (two Canvas user ids, two Moodle participants, two repositories)
    // never share a folder.
    std::map<std::string, std::string> whoseId;
    for (const engine::IntakeStudent& s : students) {
        const std::string who = platform == "canvas" ? s.canvasId : s.platformId;
        if (who.empty()) continue;
        fuzz::require(whoseId.emplace(s.id, who).first->second == who, s.id + " is the id of two students");
    }
    return 0;
}
