#include "simlab/common/files.h"

#include <dirent.h>
#include <openssl/evp.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "simlab/common/errors.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

std::string temporaryBase(const std::string& parent) {
    if (!parent.empty()) return parent;
    const char* tmp = std::getenv("TMPDIR");
    return tmp && *tmp ? tmp : "/tmp";
}

}  // namespace

TempDir::TempDir(const std::string& prefix, const std::string& parent) {
    const std::string base = temporaryBase(parent);
    std::string pattern = base + "/" + prefix + "XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (!::mkdtemp(buffer.data())) {
        throw std::runtime_error("cannot create a directory in " + base + ": " + std::strerror(errno));
    }
    path_ = buffer.data();
    // Held from before it has its name: a sweeping run sees a hold that is locked, or none.
    const std::string hold = path_ + ".held", pending = hold + ".new";
    held_ = ::open(pending.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (held_ >= 0 && (::flock(held_, LOCK_EX | LOCK_NB) != 0 || ::rename(pending.c_str(), hold.c_str()) != 0)) {
        ::unlink(pending.c_str());
        ::close(held_);
        held_ = -1;
    }
}

TempDir::~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
    if (held_ >= 0) {
        ::unlink((path_ + ".held").c_str());
        ::close(held_);
    }
}

std::vector<std::string> sweepLeftovers(const std::vector<std::string>& more) {
    std::vector<std::string> removed;
    std::vector<std::string> bases = {temporaryBase("")};
    bases.insert(bases.end(), more.begin(), more.end());
    const uid_t me = ::geteuid();
    for (const std::string& base : bases) {
        std::error_code error;
        for (auto it = fs::directory_iterator(base, error); !error && it != fs::directory_iterator(); it.increment(error)) {
            const std::string hold = it->path().string();
            const std::string name = it->path().filename().string();
            if (name.rfind("simlab-", 0) != 0 || name.size() < 12 || name.compare(name.size() - 5, 5, ".held") != 0) continue;
            const std::string folder = hold.substr(0, hold.size() - 5);
            const int fd = ::open(hold.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
            if (fd < 0) continue;
            struct stat holdInfo {}, folderInfo {};
            const bool ours = ::fstat(fd, &holdInfo) == 0 && S_ISREG(holdInfo.st_mode) && holdInfo.st_uid == me;
            if (ours && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {
                // Nobody holds it: the run that made it is gone.
                if (::lstat(folder.c_str(), &folderInfo) == 0 && S_ISDIR(folderInfo.st_mode) && folderInfo.st_uid == me) {
                    std::error_code ignored;
                    fs::remove_all(folder, ignored);
                    removed.push_back(fs::path(folder).filename().string());
                }
                ::unlink(hold.c_str());
            }
            ::close(fd);
        }
    }
    std::sort(removed.begin(), removed.end());
    return removed;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

namespace {

// How a written file may be read: `Fixed`, 0644 whatever the umask (what a sandbox's user reads); `Shared`, an output
// people share (writeOutputAtomically).
enum class Access { Fixed, Shared, Private };

void writeFileThenRename(const std::string& path, const std::string& text, bool durable,
                         Access access = Access::Fixed) {
    const std::string temporary = path + ".tmp." + std::to_string(::getpid());
    {
        // A shared output replacing a file keeps that file's mode and group (a TA's group write on manual.csv);
        // a new one has the umask's mode and the folder's group (the kernel gives a setgid folder's).
        struct stat before {};
        const bool replacing =
            access == Access::Shared && ::stat(path.c_str(), &before) == 0 && S_ISREG(before.st_mode);
        const mode_t mode = access == Access::Fixed ? 0644 : access == Access::Private || replacing ? 0600 : 0666;
        // Close-on-exec: a process another thread starts meanwhile must not keep the file open for writing (a
        // program being written would be busy, ETXTBSY, when it is run).
        const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
        if (fd < 0) throw std::runtime_error("cannot write " + temporary + ": " + std::strerror(errno));
        if (replacing) {
            // The group first (it may clear setgid bits), then the mode; either may be refused (a group the writer
            // is not in): the file is written all the same.
            (void)!::fchown(fd, static_cast<uid_t>(-1), before.st_gid);
            (void)!::fchmod(fd, before.st_mode & 0777);
        }
        std::size_t done = 0;
        while (done < text.size()) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                const int error = errno;
                ::close(fd);
                std::remove(temporary.c_str());
                throw std::runtime_error("cannot write " + temporary + ": " + std::strerror(error));
            }
            done += static_cast<std::size_t>(n);
        }
        // Durable: the bytes are on the disk before the name points to them, so that a crash or a power cut
        // leaves the old file or the new one, never a new name over an empty file.
        if (durable && ::fsync(fd) != 0) {
            const int error = errno;
            ::close(fd);
            std::remove(temporary.c_str());
            throw std::runtime_error("cannot write " + temporary + ": " + std::strerror(error));
        }
        ::close(fd);
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const int error = errno;
        std::remove(temporary.c_str());
        throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
    }
    if (durable) {
        // And the rename itself: the folder's entry.
        const std::string folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path().string() : ".";
        const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (dir >= 0) {
            ::fsync(dir);
            ::close(dir);
        }
    }
}

}  // namespace

void createPrivateFolder(const std::string& path) {
    if (::mkdir(path.c_str(), 0700) == 0) return;
    const int error = errno;
    struct stat info {};
    if (error == EEXIST && ::lstat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
        if (::chmod(path.c_str(), 0700) == 0) return;
        throw std::runtime_error("cannot keep the folder " + path + " private: " + std::strerror(errno) +
                                 (info.st_uid != ::geteuid() ? " (it is another user's)" : ""));
    }
    throw std::runtime_error("cannot create the folder " + path + ": " + std::strerror(error));
}

void closeToOthers(const std::string& path) {
    std::error_code error;
    if (!fs::exists(path, error)) return;
    const auto close = [&](const fs::path& p) {
        fs::permissions(p, fs::perms::group_all | fs::perms::others_all, fs::perm_options::remove, error);
    };
    close(path);
    if (!fs::is_directory(path, error)) return;
    for (auto it = fs::recursive_directory_iterator(path, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        close(it->path());
    }
}

void writeFileAtomically(const std::string& path, const std::string& text) { writeFileThenRename(path, text, false); }

void writeFileDurably(const std::string& path, const std::string& text) { writeFileThenRename(path, text, true); }

void writeOutputAtomically(const std::string& path, const std::string& text) {
    writeFileThenRename(path, text, false, Access::Shared);
}

void writeOutputDurably(const std::string& path, const std::string& text) {
    writeFileThenRename(path, text, true, Access::Shared);
}

void writePrivateAtomically(const std::string& path, const std::string& text) {
    writeFileThenRename(path, text, false, Access::Private);
    ::chmod(path.c_str(), 0600);  // a file it replaced may have had another mode
}

void createOutputFolder(const std::string& path) {
    std::error_code error;
    if (fs::is_directory(path, error)) return;
    const fs::path parent = fs::absolute(path, error).lexically_normal().parent_path();
    if (!parent.empty()) fs::create_directories(parent, error);
    // Grades are the course's staff's: the owner's and the group's (a setgid parent's), never every user's.
    if (::mkdir(path.c_str(), 0770) != 0 && errno != EEXIST) {
        throw std::runtime_error("cannot create the folder " + path + ": " + std::strerror(errno));
    }
}

OutputLock::OutputLock(const std::string& folder, const std::string& shard) {
    const std::string path = folder + "/.simlab-lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
    if (::flock(fd_, (shard.empty() ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0) {
        const int error = errno;
        std::string holder = readFile(path);
        holder = holder.substr(0, holder.find('\n'));
        ::close(fd_);
        fd_ = -1;
        if (error == EWOULDBLOCK) {
            throw UsageError("another simlab is writing into " + folder +
                             (holder.empty() ? "" : " (process " + holder + ")") +
                             ": wait for it to finish, or give another --out");
        }
        throw std::runtime_error("cannot lock " + path + ": " + std::strerror(error));
    }
    // Who holds it, for the message another simlab gives; the lock itself is the kernel's, and ends with us.
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
        // The lock holds all the same; only another simlab's message lacks the process number.
    }
    if (shard.empty()) return;
    const std::string shardPath = path + "-shard-" + shard;
    shardFd_ = ::open(shardPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (shardFd_ < 0) {
        const int error = errno;
        ::close(fd_);
        fd_ = -1;
        throw std::runtime_error("cannot open " + shardPath + ": " + std::strerror(error));
    }
    if (::flock(shardFd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        std::string holder = readFile(shardPath);
        holder = holder.substr(0, holder.find('\n'));
        ::close(shardFd_);
        ::close(fd_);
        shardFd_ = fd_ = -1;
        if (error == EWOULDBLOCK) {
            throw UsageError("shard " + shard + " of " + folder + " is being graded already" +
                             (holder.empty() ? "" : " (process " + holder + ")"));
        }
        throw std::runtime_error("cannot lock " + shardPath + ": " + std::strerror(error));
    }
    if (::ftruncate(shardFd_, 0) != 0 || ::pwrite(shardFd_, pid.data(), pid.size(), 0) < 0) {
        // as above
    }
}

OutputLock::~OutputLock() {
    if (shardFd_ >= 0) ::close(shardFd_);
    if (fd_ >= 0) ::close(fd_);
}

Hash::Hash() : context_(EVP_MD_CTX_new()) {
    if (!context_ || EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(context_), EVP_sha256(), nullptr) != 1) {
        throw std::runtime_error("cannot start a SHA-256 hash");
    }
}

Hash::~Hash() { EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(context_)); }

Hash::Hash(const Hash& other) : context_(EVP_MD_CTX_new()) {
    if (!context_ || EVP_MD_CTX_copy_ex(static_cast<EVP_MD_CTX*>(context_), static_cast<EVP_MD_CTX*>(other.context_)) != 1) {
        throw std::runtime_error("cannot copy a SHA-256 hash");
    }
}

Hash& Hash::operator=(const Hash& other) {
    if (this != &other) EVP_MD_CTX_copy_ex(static_cast<EVP_MD_CTX*>(context_), static_cast<EVP_MD_CTX*>(other.context_));
    return *this;
}

Hash& Hash::add(const std::string& bytes) {
    // Each field is its length, then its bytes: no two sequences of fields hash the same input.
    const std::string length = std::to_string(bytes.size()) + ":";
    EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(context_), length.data(), length.size());
    EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(context_), bytes.data(), bytes.size());
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

namespace {
std::string hexOf(const unsigned char* digest, unsigned int size);
}  // namespace

Hash& Hash::addFileContent(const std::string& path) {
    // Known digests by device, inode, size and modification time: a file read once is not read again while it
    // stays as it was.
    static std::mutex lock;
    static std::map<std::string, std::string> known;
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return add("(missing)");
    const std::string stamp = std::to_string(info.st_dev) + ":" + std::to_string(info.st_ino) + ":" +
                              std::to_string(info.st_size) + ":" + std::to_string(info.st_mtim.tv_sec) + "." +
                              std::to_string(info.st_mtim.tv_nsec);
    {
        std::lock_guard<std::mutex> guard(lock);
        if (const auto found = known.find(stamp); found != known.end()) return add(found->second);
    }
    // Read in pieces: a precompiled header is hundreds of megabytes.
    EVP_MD_CTX* context = EVP_MD_CTX_new();
    if (!context || EVP_DigestInit_ex(context, EVP_sha256(), nullptr) != 1) {
        EVP_MD_CTX_free(context);
        throw std::runtime_error("cannot start a SHA-256 hash");
    }
    std::ifstream in(path, std::ios::binary);
    std::vector<char> piece(1 << 20);
    while (in) {
        in.read(piece.data(), static_cast<std::streamsize>(piece.size()));
        EVP_DigestUpdate(context, piece.data(), static_cast<std::size_t>(in.gcount()));
    }
    unsigned char bytes[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    const bool read = in.eof() && !in.bad();
    const bool done = EVP_DigestFinal_ex(context, bytes, &size) == 1;
    EVP_MD_CTX_free(context);
    if (!read || !done) throw std::runtime_error("cannot read " + path + " to hash it");
    const std::string digest = hexOf(bytes, size);
    std::lock_guard<std::mutex> guard(lock);
    known[stamp] = digest;
    return add(digest);
}

namespace {

std::string hexOf(const unsigned char* digest, unsigned int size) {
    static const char* digits = "0123456789abcdef";
    std::string text;
    for (unsigned int i = 0; i < size; ++i) {
        text += digits[digest[i] >> 4];
        text += digits[digest[i] & 15];
    }
    return text;
}

}  // namespace

std::string Hash::hex() const {
    EVP_MD_CTX* copy = EVP_MD_CTX_new();
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (!copy || EVP_MD_CTX_copy_ex(copy, static_cast<EVP_MD_CTX*>(context_)) != 1 ||
        EVP_DigestFinal_ex(copy, digest, &size) != 1) {
        EVP_MD_CTX_free(copy);
        throw std::runtime_error("cannot finish a SHA-256 hash");
    }
    EVP_MD_CTX_free(copy);
    return hexOf(digest, size);
}

std::string sha256Hex(const std::string& bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1) {
        throw std::runtime_error("cannot compute a SHA-256 hash");
    }
    return hexOf(digest, size);
}

namespace {

// A descriptor closed when it goes out of scope.
struct Descriptor {
    int fd = -1;
    explicit Descriptor(int f) : fd(f) {}
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
};

int openFolder(const std::string& folder, bool followFolder) {
    return ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | (followFolder ? 0 : O_NOFOLLOW));
}

std::string whatItIs(mode_t mode) {
    if (S_ISLNK(mode)) return "a symbolic link";
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a named pipe";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

EntryType typeOf(mode_t mode) {
    if (S_ISREG(mode)) return EntryType::Regular;
    if (S_ISDIR(mode)) return EntryType::Directory;
    if (S_ISLNK(mode)) return EntryType::Symlink;
    return EntryType::Other;
}

}  // namespace

std::string byteSize(std::uint64_t bytes) {
    char text[32];
    if (bytes >= (1ull << 30)) std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(1ull << 30));
    else if (bytes >= (1ull << 20)) std::snprintf(text, sizeof text, "%.1f MiB", bytes / double(1ull << 20));
    else if (bytes >= 1024) std::snprintf(text, sizeof text, "%.0f KiB", bytes / 1024.0);
    else std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
    return text;
}

HandedIn readHandedIn(const std::string& folder, const std::string& name, std::size_t limit, bool followFolder) {
    HandedIn file;
    file.name = name;
    const SubmissionStatus unsafe = SubmissionStatus::UnsafeFile, tooLarge = SubmissionStatus::FileTooLarge;
    auto refuse = [&](SubmissionStatus status, const std::string& why) {
        file.status = status;
        file.refusal = name + " " + why;
        return file;
    };
    const Descriptor dir(openFolder(folder, followFolder));
    if (dir.fd < 0) {
        file.found = errno != ENOENT;
        return file.found ? refuse(unsafe, "is in a folder that cannot be opened (" +
                                                      std::string(std::strerror(errno)) + ")")
                          : file;
    }
    struct stat seen {};
    if (::fstatat(dir.fd, name.c_str(), &seen, AT_SYMLINK_NOFOLLOW) != 0) return file;  // not there
    file.found = true;
    if (!S_ISREG(seen.st_mode)) return refuse(unsafe, "is " + whatItIs(seen.st_mode) + "; hand in the file itself");
    if (static_cast<std::uint64_t>(seen.st_size) > limit) {
        return refuse(tooLarge, "is " + byteSize(seen.st_size) + "; the limit is " + byteSize(limit));
    }
    // A second name for a file others may not read (/etc/shadow, say) is not read with root's privilege.
    if (::geteuid() == 0 && seen.st_nlink > 1 && !(seen.st_mode & S_IROTH)) {
        return refuse(unsafe, "is a hard link to a file that others may not read; hand in a copy");
    }
    const Descriptor in(::openat(dir.fd, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
    struct stat opened {};
    if (in.fd < 0 || ::fstat(in.fd, &opened) != 0) {
        return refuse(unsafe, "cannot be read (" + std::string(std::strerror(errno)) + ")");
    }
    if (!S_ISREG(opened.st_mode) || opened.st_ino != seen.st_ino || opened.st_dev != seen.st_dev) {
        return refuse(unsafe, "changed while it was being read");
    }
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(in.fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return refuse(unsafe, "cannot be read (" + std::string(std::strerror(errno)) + ")");
        if (n == 0) break;
        file.text.append(buffer, static_cast<std::size_t>(n));
        if (file.text.size() > limit) {
            file.text.clear();
            return refuse(tooLarge, "is over the limit of " + byteSize(limit));
        }
    }
    file.ok = true;
    return file;
}

std::vector<FolderEntry> listFolder(const std::string& folder, bool followFolder) {
    const int fd = openFolder(folder, followFolder);
    if (fd < 0) throw std::runtime_error("cannot open the folder " + folder + ": " + std::strerror(errno));
    DIR* dir = ::fdopendir(fd);
    if (!dir) {
        ::close(fd);
        throw std::runtime_error("cannot list the folder " + folder + ": " + std::strerror(errno));
    }
    std::vector<FolderEntry> entries;
    while (const struct dirent* e = ::readdir(dir)) {
        const std::string name = e->d_name;
        if (name == "." || name == "..") continue;
        struct stat info {};
        const EntryType type =
            ::fstatat(::dirfd(dir), e->d_name, &info, AT_SYMLINK_NOFOLLOW) == 0 ? typeOf(info.st_mode) : EntryType::Other;
        entries.push_back({name, folder, type});
    }
    ::closedir(dir);
    std::sort(entries.begin(), entries.end(), [](const FolderEntry& a, const FolderEntry& b) { return a.name < b.name; });
    return entries;
}

std::vector<FolderEntry> walkFolder(const std::string& folder) {
    constexpr int kMaxDepth = 8;
    constexpr std::size_t kMaxEntries = 10000;
    std::vector<FolderEntry> all;
    struct Pending {
        std::string path, relative;
        int depth;
    };
    std::vector<Pending> queue = {{folder, "", 0}};
    for (std::size_t next = 0; next < queue.size() && all.size() < kMaxEntries; ++next) {
        const Pending here = queue[next];
        std::vector<FolderEntry> entries;
        try {
            entries = listFolder(here.path, here.depth == 0);
        } catch (const std::exception&) {
            continue;  // a subfolder that cannot be listed holds nothing we can grade
        }
        for (FolderEntry& e : entries) {
            if (all.size() >= kMaxEntries) break;
            const std::string relative = here.relative.empty() ? e.name : here.relative + "/" + e.name;
            if (e.type == EntryType::Directory && here.depth + 1 < kMaxDepth) {
                queue.push_back({here.path + "/" + e.name, relative, here.depth + 1});
            }
            e.name = relative;
            all.push_back(e);
        }
    }
    std::sort(all.begin(), all.end(), [](const FolderEntry& a, const FolderEntry& b) { return a.name < b.name; });
    return all;
}

void requireCppSource(const std::string& path) {
    // Whether it is a regular file, readable and not too large is for readHandedIn to say, without following it.
    std::error_code error;
    const fs::file_status status = fs::symlink_status(path, error);
    if (!fs::exists(status)) throw UsageError("source file '" + path + "' does not exist");
    if (fs::is_directory(status)) throw UsageError("'" + path + "' is a directory, not a C++ source file");
    const std::string extension = fs::path(path).extension().string();
    if (extension != ".cpp" && extension != ".cc" && extension != ".cxx" && extension != ".c++" && extension != ".C") {
        throw UsageError("'" + path + "' is not a C++ source file (expected .cpp, .cc or .cxx)");
    }
}

}  // namespace simlab::engine
