// Small file-system helpers the engine shares.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simlab/common/status.h"

namespace simlab::engine {

/// A fresh private directory, removed with everything in it when this object goes.
class TempDir {
public:
    /// Creates <parent>/<prefix>XXXXXX (0700); parent defaults to $TMPDIR or /tmp. Beside it, <that>.held stays
    /// locked (flock) while this process lives: a run stopped for good (SIGKILL, a power cut) leaves the folder
    /// unheld, for the next run to sweep (sweepLeftovers).
    explicit TempDir(const std::string& prefix, const std::string& parent = "");
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
    int held_ = -1;
};

/// The folders runs of simlab stopped for good left in $TMPDIR (or /tmp), and in `more`: each a TempDir whose
/// hold nobody keeps, owned by this process's user. Removed, with their holds; their names are returned. Never
/// touches another user's folder, a folder a live run holds, or anything a link leads to.
std::vector<std::string> sweepLeftovers(const std::vector<std::string>& more = {});

/// A folder only its owner may enter (0700) from the moment it exists, so that nothing written into it is ever
/// another user's to read; a folder already there is closed to others. Throws std::runtime_error on failure.
void createPrivateFolder(const std::string& path);

/// `path`, and everything below it if a folder, closed to group and others (what no test's code may read, where no
/// sandbox hides it). Nothing there is no error.
void closeToOthers(const std::string& path);

/// The whole file; throws std::runtime_error naming the file and the reason.
std::string readFile(const std::string& path);
/// Write `text` to `path` atomically: a temporary file in the same directory, renamed over `path`.
void writeFileAtomically(const std::string& path, const std::string& text);
/// The same, and durable: the file's bytes and then its folder's entry are flushed to the disk (fsync), so that
/// after a crash or a power cut `path` holds the old text or the new one. For the files that commit a grade.
void writeFileDurably(const std::string& path, const std::string& text);
/// The same two for a file people share, an output of grading (the gradebook, manual.csv, the reports, a student's
/// feedback): its mode as the umask gives (0666 less it) and its group the folder's (a setgid folder's), or, where it
/// replaces a file, that file's mode and group, so that a TA of the course's group who may edit manual.csv in place
/// still may after simlab wrote it again.
void writeOutputAtomically(const std::string& path, const std::string& text);
void writeOutputDurably(const std::string& path, const std::string& text);
/// The same for a file of simlab's own (a cache's): its owner's alone (0600), whatever the umask.
void writePrivateAtomically(const std::string& path, const std::string& text);

/// A folder of grades, made if missing (with the folders above it): its owner's and its group's (0770 less the
/// umask), never every user's - where files are kept apart by their modes alone, a test's throwaway user must not
/// reach what simlab writes there later.
void createOutputFolder(const std::string& path);

/// A hold on a folder simlab writes into (`folder`/.simlab-lock, flock): a second simlab given the same folder
/// stops with a UsageError naming the first one's process. Released when destroyed or when the process ends.
/// A shard (`shard` not empty, "2-of-3" say) shares the folder with the other shards, each writing only its own
/// students, and holds `folder`/.simlab-lock-shard-`shard` alone: shards run side by side, a second copy of one
/// shard stops, and a whole-class simlab (which writes the gradebook) waits for none of them but stops while any
/// runs.
class OutputLock {
public:
    explicit OutputLock(const std::string& folder, const std::string& shard = "");
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

private:
    int fd_ = -1;
    int shardFd_ = -1;
};

/// SHA-256 of the fields added, for cache and resume keys: a student must not be able to make two files share a
/// key (with a weak hash, a crafted starter could take a finished file's cached object, or its grade).
class Hash {
public:
    Hash();
    ~Hash();
    Hash(const Hash& other);
    Hash& operator=(const Hash& other);
    /// Adds `bytes` as one field: ("ab", "c") and ("a", "bc") differ.
    Hash& add(const std::string& bytes);
    /// Adds the file's path, size and modification time (cheap; enough to notice a rebuilt file).
    Hash& addFileStamp(const std::string& path);
    /// Adds the SHA-256 of the file's content, not its path or times: the same bytes anywhere hash the same. Each
    /// file is read once per process (while its size and time stay the same). A missing file adds "(missing)".
    Hash& addFileContent(const std::string& path);
    /// 64 hexadecimal digits. The hash can go on being added to afterwards.
    std::string hex() const;

private:
    void* context_;  // OpenSSL's EVP_MD_CTX
};

/// The SHA-256 of `bytes` alone, in 64 hexadecimal digits (as sha256sum prints it).
std::string sha256Hex(const std::string& bytes);

/// A file a student handed in, read as data (readHandedIn).
struct HandedIn {
    std::string name;     ///< its name in the folder
    bool found = false;   ///< an entry of that name exists
    bool ok = false;      ///< read: `text` holds it
    std::string text;
    std::optional<SubmissionStatus> status;  ///< when found but not read: UnsafeFile or FileTooLarge
    std::string refusal;  ///< why, in one line: "NewtonsApple.cpp is a symbolic link; hand in the file itself"
};

/// Read `name` from the folder `folder` as untrusted data: a regular file only - a symbolic link, folder, named
/// pipe, device or socket is refused without being opened or followed, as is a hard link to a file that others
/// may not read when simlab runs as root - opened without following links and without blocking, and at most
/// `limit` bytes (larger is refused, unread). `followFolder` false: `folder` itself must not be a symbolic link
/// either (a student's folder); true: it is a path the user named.
HandedIn readHandedIn(const std::string& folder, const std::string& name, std::size_t limit, bool followFolder);

/// What lstat says an entry of a folder is.
enum class EntryType { Regular, Directory, Symlink, Other };
struct FolderEntry {
    std::string name;      ///< relative to the folder listed (with '/' below it, for walkFolder)
    std::string folder;    ///< the folder that holds it
    EntryType type = EntryType::Other;
};
/// The entries of `folder` (not "." or ".."), sorted by name, without following any link. `followFolder` as for
/// readHandedIn. Throws std::runtime_error if the folder cannot be opened.
std::vector<FolderEntry> listFolder(const std::string& folder, bool followFolder);
/// The entries of `folder` and of its subfolders, never following a link, to a depth of 8 and at most 10000
/// entries (what lies beyond is left out).
std::vector<FolderEntry> walkFolder(const std::string& folder);

/// "3.0 GiB", "12 KiB", "512 bytes".
std::string byteSize(std::uint64_t bytes);

/// Checks that `path` names something that exists, is not a folder and has a C++ source file's extension (.cpp,
/// .cc, .cxx, .c++ or .C). Throws UsageError with one line saying what is wrong otherwise. (Reading it is for
/// readHandedIn, which refuses what is not a regular file.)
void requireCppSource(const std::string& path);

}  // namespace simlab::engine
