// Small file-system helpers the engine shares.
#pragma once

#include <cstdint>
#include <string>

namespace simlab::engine {

/// A fresh private directory, removed with everything in it when this object goes.
class TempDir {
public:
    /// Creates <parent>/<prefix>XXXXXX; parent defaults to $TMPDIR or /tmp.
    explicit TempDir(const std::string& prefix, const std::string& parent = "");
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

/// The whole file; throws std::runtime_error naming the file and the reason.
std::string readFile(const std::string& path);
/// Write `text` to `path` atomically: a temporary file in the same directory, renamed over `path`.
void writeFileAtomically(const std::string& path, const std::string& text);

/// 64-bit FNV-1a, for change detection (not security).
class Hash {
public:
    Hash& add(const std::string& bytes);
    /// Adds the file's path, size and modification time (cheap; enough to notice a rebuilt file).
    Hash& addFileStamp(const std::string& path);
    std::uint64_t value() const { return state_; }
    std::string hex() const;

private:
    std::uint64_t state_ = 1469598103934665603ull;
};

/// Checks that `path` names a readable C++ source file (.cpp, .cc, .cxx, .c++ or .C). Throws UsageError with
/// one line saying what is wrong otherwise.
void requireCppSource(const std::string& path);

}  // namespace simlab::engine
