// What the fuzz targets share (tests/fuzz/<reader>.cpp, each a libFuzzer target, LLVMFuzzerTestOneInput): an input
// as text, an input in parts, a folder of the target's own for readers that take files, and a property's failure.
//
// A target feeds its reader the bytes as they would reach it - a file's text, a line on a channel, a folder laid out
// as a download - and fails (abort, which libFuzzer keeps as a crash) only where the reader misbehaves: a sanitizer's
// report, an exception other than the reader's one-line error, a hang, or a property the target states (what simlab
// writes reads back the same, say). A reader's refusal of bad bytes is what it is for.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace simlab::fuzz {

/// The input as a string of its bytes.
inline std::string text(const std::uint8_t* data, std::size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

/// The input cut at each `separator` (a line of its own, such as "\n%%\n"): at most `most` parts, the last one
/// keeping the rest.
inline std::vector<std::string> parts(const std::string& input, const std::string& separator, std::size_t most) {
    std::vector<std::string> out;
    std::size_t at = 0;
    while (out.size() + 1 < most) {
        const std::size_t next = input.find(separator, at);
        if (next == std::string::npos) break;
        out.push_back(input.substr(at, next - at));
        at = next + separator.size();
    }
    out.push_back(input.substr(at));
    return out;
}

/// A property the target states does not hold: says which, with the input's size, and aborts (a crash to libFuzzer).
[[noreturn]] inline void broken(const std::string& what) {
    std::fprintf(stderr, "fuzz: property broken: %s\n", what.c_str());
    std::abort();
}

inline void require(bool holds, const std::string& what) {
    if (!holds) broken(what);
}

/// A folder of this process's own for the files a reader takes (in $TMPDIR, else /tmp), emptied before each input
/// and removed when the process ends.
class Scratch {
public:
    Scratch() {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/simlab-fuzz-XXXXXX";
        if (!::mkdtemp(pattern.data())) broken("no scratch folder");
        root_ = pattern;
    }
    ~Scratch() {
        std::error_code ignored;
        std::filesystem::remove_all(root_, ignored);
    }
    /// The folder, emptied (what a reader left, links and folders closed to their owner included).
    const std::string& fresh() {
        std::error_code ignored;
        for (const auto& e : std::filesystem::directory_iterator(root_, ignored)) {
            std::filesystem::permissions(e.path(), std::filesystem::perms::owner_all,
                                         std::filesystem::perm_options::add | std::filesystem::perm_options::nofollow,
                                         ignored);
            std::filesystem::remove_all(e.path(), ignored);
        }
        return root_;
    }
    const std::string& path() const { return root_; }

private:
    std::string root_;
};

/// One scratch folder per process.
inline Scratch& scratch() {
    static Scratch s;
    return s;
}

/// Writes `bytes` to `path` (created or emptied), failing the target if it cannot.
inline void write(const std::string& path, const std::string& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0600);
    if (fd < 0) broken("cannot write " + path);
    for (std::size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n <= 0) broken("cannot write " + path);
        done += static_cast<std::size_t>(n);
    }
    ::close(fd);
}

}  // namespace simlab::fuzz
