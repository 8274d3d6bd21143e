#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "internal.h"

namespace simlab::isolation::landlock {

namespace {

// The constants of linux/landlock.h up to ABI 6, spelled out: Debian 12's kernel headers stop at ABI 2.

constexpr std::uint64_t kExecute = 1ULL << 0, kWriteFile = 1ULL << 1, kReadFile = 1ULL << 2, kReadDir = 1ULL << 3,
                        kRemoveDir = 1ULL << 4, kRemoveFile = 1ULL << 5, kMakeChar = 1ULL << 6,
                        kMakeDir = 1ULL << 7, kMakeReg = 1ULL << 8, kMakeSock = 1ULL << 9, kMakeFifo = 1ULL << 10,
                        kMakeBlock = 1ULL << 11, kMakeSym = 1ULL << 12, kRefer = 1ULL << 13,
                        kTruncate = 1ULL << 14, kIoctlDev = 1ULL << 15;
constexpr std::uint64_t kBindTcp = 1ULL << 0, kConnectTcp = 1ULL << 1;
constexpr std::uint64_t kScopeAbstractSocket = 1ULL << 0, kScopeSignal = 1ULL << 1;
constexpr int kRulePathBeneath = 1;
constexpr unsigned kCreateRulesetVersion = 1U << 0;

struct RulesetAttr {
    std::uint64_t handledFs;
    std::uint64_t handledNet;
    std::uint64_t scoped;
};

struct __attribute__((packed)) PathBeneathAttr {
    std::uint64_t allowed;
    std::int32_t parentFd;
};

#ifndef SYS_landlock_create_ruleset
#define SYS_landlock_create_ruleset 444
#define SYS_landlock_add_rule 445
#define SYS_landlock_restrict_self 446
#endif

// Every file-system right the kernel's ABI knows.
std::uint64_t fsRights(int abi) {
    std::uint64_t rights = kExecute | kWriteFile | kReadFile | kReadDir | kRemoveDir | kRemoveFile | kMakeChar |
                           kMakeDir | kMakeReg | kMakeSock | kMakeFifo | kMakeBlock | kMakeSym;
    if (abi >= 2) rights |= kRefer;
    if (abi >= 3) rights |= kTruncate;
    if (abi >= 5) rights |= kIoctlDev;
    return rights;
}

bool addRule(int ruleset, const std::string& path, std::uint64_t dirRights, std::uint64_t fileRights, int abi,
             std::string* error) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return true;  // nothing there to allow
    const int fd = ::open(path.c_str(), O_PATH | O_CLOEXEC);
    if (fd < 0) return true;
    PathBeneathAttr rule{(S_ISDIR(info.st_mode) ? dirRights : fileRights) & fsRights(abi), fd};
    const bool ok = ::syscall(SYS_landlock_add_rule, ruleset, kRulePathBeneath, &rule, 0) == 0;
    if (!ok && error) *error = "Landlock refused a rule for " + path + ": " + std::strerror(errno);
    ::close(fd);
    return ok;
}

}  // namespace

int abi() {
    static const int version = [] {
        const long answer = ::syscall(SYS_landlock_create_ruleset, nullptr, 0, kCreateRulesetVersion);
        return answer > 0 ? static_cast<int>(answer) : 0;
    }();
    return version;
}

int makeRuleset(const FileRules& rules, std::string* error) {
    const int version = abi();
    if (version == 0) {
        if (error) *error = "this kernel has no Landlock, or it is blocked here";
        return -1;
    }
    RulesetAttr attr{fsRights(version), version >= 4 ? kBindTcp | kConnectTcp : 0,
                     version >= 6 ? kScopeAbstractSocket | kScopeSignal : 0};
    // The attribute's size says which fields this kernel reads.
    const std::size_t size = version >= 6 ? sizeof attr : version >= 4 ? 2 * sizeof(std::uint64_t) : sizeof(std::uint64_t);
    const int ruleset = static_cast<int>(::syscall(SYS_landlock_create_ruleset, &attr, size, 0));
    if (ruleset < 0) {
        if (error) *error = std::string("cannot create a Landlock ruleset: ") + std::strerror(errno);
        return -1;
    }
    ::fcntl(ruleset, F_SETFD, FD_CLOEXEC);
    const std::uint64_t read = kExecute | kReadFile | kReadDir;
    const std::uint64_t write = fsRights(version) & ~(kMakeChar | kMakeBlock | kMakeSock);
    const std::uint64_t device = kReadFile | kWriteFile | kTruncate | kIoctlDev;
    bool ok = true;
    for (const std::string& path : rules.readable) ok = ok && addRule(ruleset, path, read, kExecute | kReadFile, version, error);
    for (const std::string& path : rules.writable) ok = ok && addRule(ruleset, path, write, write, version, error);
    for (const std::string& path : rules.devices) ok = ok && addRule(ruleset, path, device, device, version, error);
    if (!ok) {
        ::close(ruleset);
        return -1;
    }
    return ruleset;
}

bool restrictSelf(int ruleset) {
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) return false;
    return ::syscall(SYS_landlock_restrict_self, ruleset, 0) == 0;
}

}  // namespace simlab::isolation::landlock
