#include "simlab/engine/files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "simlab/engine/errors.h"

namespace fs = std::filesystem;

namespace simlab::engine {

TempDir::TempDir(const std::string& prefix, const std::string& parent) {
    std::string base = parent;
    if (base.empty()) {
        const char* tmp = std::getenv("TMPDIR");
        base = tmp && *tmp ? tmp : "/tmp";
    }
    std::string pattern = base + "/" + prefix + "XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (!::mkdtemp(buffer.data())) {
        throw std::runtime_error("cannot create a directory in " + base + ": " + std::strerror(errno));
    }
    path_ = buffer.data();
}

TempDir::~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void writeFileAtomically(const std::string& path, const std::string& text) {
    const std::string temporary = path + ".tmp." + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) throw std::runtime_error("cannot write " + temporary + ": " + std::strerror(errno));
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const int error = errno;
        std::remove(temporary.c_str());
        throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
    }
}

Hash& Hash::add(const std::string& bytes) {
    for (unsigned char c : bytes) {
        state_ ^= c;
        state_ *= 1099511628211ull;
    }
    // Separate consecutive fields so ("ab", "c") and ("a", "bc") differ.
    state_ ^= 0xff;
    state_ *= 1099511628211ull;
    return *this;
}

Hash& Hash::addFileStamp(const std::string& path) {
    struct stat info {};
    add(path);
    if (::stat(path.c_str(), &info) == 0) {
        add(std::to_string(info.st_size) + ":" + std::to_string(info.st_mtim.tv_sec) + "." +
            std::to_string(info.st_mtim.tv_nsec));
    }
    return *this;
}

std::string Hash::hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
    return text;
}

void requireCppSource(const std::string& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) throw UsageError("source file '" + path + "' does not exist");
    if (fs::is_directory(status)) throw UsageError("'" + path + "' is a directory, not a C++ source file");
    if (!fs::is_regular_file(status)) throw UsageError("'" + path + "' is not a regular file");
    const std::string extension = fs::path(path).extension().string();
    if (extension != ".cpp" && extension != ".cc" && extension != ".cxx" && extension != ".c++" && extension != ".C") {
        throw UsageError("'" + path + "' is not a C++ source file (expected .cpp, .cc or .cxx)");
    }
    if (::access(path.c_str(), R_OK) != 0) {
        throw UsageError("cannot read '" + path + "': " + std::strerror(errno));
    }
}

}  // namespace simlab::engine
