// Where a test's student code was when it failed, told by the probe's host on the event channel as the probe's frames
// (simlab/isolation/failure_sites.h). Everything that runs in a signal handler here is async-signal-safe: system
// calls, a fixed buffer, and libgcc's unwinder, which finds each frame's unwind table with _dl_find_object (made for
// signal handlers) once its one-time set-up has run, which watchFailureSites does before any handler can.
#include "failure_sites.h"

#include <dlfcn.h>
#include <link.h>
#include <setjmp.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>
#include <unwind.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <typeinfo>

#include "simlab/isolation/failure_sites.h"
#include "simlab/isolation/host_protocol.h"

namespace simlab::isolation::host {

namespace {

constexpr int kMaxWalk = 256;                     // frames walked, at most, to find the probe's
constexpr long kSampleNanoseconds = 100000000;    // the sampler's period, of the process's CPU time
constexpr int kSampleSignal = SIGURG;             // its signal: one whose default is to be ignored, so that code
                                                  // that resets every handler is not ended by a sample
constexpr std::size_t kAlternateStack = 64 * 1024;  // for a handler when the stack overflowed

char gProbe[4096];       // the probe's path as the host loads it: the loader names the module by it
bool gWatching = false;  // set once the watches are in place (in the test's process)

struct Frames {
    int count = 0;
    std::uint64_t at[kMaxFailureFrames];
};

// A walk under way on this thread, and where a fault during it goes: the walk ends there, never the process.
thread_local bool tWalking = false;
thread_local sigjmp_buf tGiveUp;

struct Walk {
    Frames* frames;
    int walked;
};

// Each frame of the walk: kept when it lies in the probe, as an address in the probe's file.
_Unwind_Reason_Code onFrame(struct _Unwind_Context* context, void* data) {
    Walk& w = *static_cast<Walk*>(data);
    if (++w.walked > kMaxWalk || w.frames->count == kMaxFailureFrames) return _URC_END_OF_STACK;
    int beforeInstruction = 0;
    std::uintptr_t pc = _Unwind_GetIPInfo(context, &beforeInstruction);
    if (pc == 0) return _URC_END_OF_STACK;
    if (!beforeInstruction) --pc;  // a return address: the call the frame made ends just before it
    struct dl_find_object found;
    // The unwinder gives the address as a number; the loader takes it as a pointer.
    void* address = reinterpret_cast<void*>(pc);  // NOLINT(performance-no-int-to-ptr)
    if (::_dl_find_object(address, &found) != 0 || !found.dlfo_link_map) return _URC_NO_REASON;
    const struct link_map* module = found.dlfo_link_map;
    if (!module->l_name || std::strcmp(module->l_name, gProbe) != 0) return _URC_NO_REASON;
    const std::uint64_t at = pc - module->l_addr;
    if (at < kMaxFailureAddress) w.frames->at[w.frames->count++] = at;
    return _URC_NO_REASON;
}

// The calling thread's frames in the probe, innermost first (those found before a fault, should the walk meet one).
void walk(Frames& frames) {
    frames.count = 0;
    if (!gWatching || tWalking) return;
    tWalking = true;
    if (::sigsetjmp(tGiveUp, 1) == 0) {
        Walk w{&frames, 0};
        _Unwind_Backtrace(onFrame, &w);
    }
    tWalking = false;
}

// One event line in a fixed buffer; no allocation.
class Line {
public:
    void add(const char* text) {
        for (; *text && used_ + 2 < sizeof text_; ++text) text_[used_++] = *text;
    }
    void add(std::uint64_t number) {
        char digits[24];
        int n = 0;
        do {
            digits[n++] = static_cast<char>('0' + number % 10);
            number /= 10;
        } while (number > 0);
        while (n > 0 && used_ + 2 < sizeof text_) text_[used_++] = digits[--n];
    }
    void frames(const Frames& f) {
        add("\"at\":[");
        for (int i = 0; i < f.count; ++i) {
            if (i > 0) add(",");
            add(f.at[i]);
        }
        add("]}");
    }
    void send() {
        text_[used_++] = '\n';
        (void)!::write(kEventFd, text_, used_);
    }

private:
    char text_[512];
    std::size_t used_ = 0;
};

void onFatalSignal(int signal, siginfo_t*, void*) {
    if (tWalking) ::siglongjmp(tGiveUp, 1);  // the walk of another watch met a bad frame: that walk ends
    tellFailureSite(signal);
    endAs(signal);
}

// The sampler's tick: where the process is after each tenth of a second of CPU time. A SIGURG that is not the
// timer's is ignored, as by default.
void onSample(int, siginfo_t* info, void*) {
    if (!info || info->si_code != SI_TIMER) return;
    const int saved = errno;
    struct timespec used {};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &used);
    Frames frames;
    walk(frames);
    if (frames.count > 0) {
        Line line;
        line.add("{\"event\":\"sample\",\"cpu\":");
        line.add(static_cast<std::uint64_t>(used.tv_sec) * 1000000 + static_cast<std::uint64_t>(used.tv_nsec) / 1000);
        line.add(",");
        line.frames(frames);
        line.send();
    }
    errno = saved;
}

// The CPU time sampler: from half the test's limit on (each process's RLIMIT_CPU is the limit rounded up plus two
// seconds, host::setLimits), so that the last sample before the engine stops the test is at most a tenth of a
// second of CPU time before it.
void startSampler() {
    struct rlimit cpu {};
    if (::getrlimit(RLIMIT_CPU, &cpu) != 0 || cpu.rlim_cur == RLIM_INFINITY || cpu.rlim_cur <= 2) return;
    const long long start = static_cast<long long>(cpu.rlim_cur - 2) * 500000000LL;  // half, in nanoseconds
    struct sigevent event {};
    event.sigev_notify = SIGEV_SIGNAL;
    event.sigev_signo = kSampleSignal;
    timer_t timer;
    if (::timer_create(CLOCK_PROCESS_CPUTIME_ID, &event, &timer) != 0) return;
    struct itimerspec when {};
    when.it_value.tv_sec = static_cast<time_t>(start / 1000000000LL);
    when.it_value.tv_nsec = static_cast<long>(start % 1000000000LL);
    when.it_interval.tv_nsec = kSampleNanoseconds;
    ::timer_settime(timer, 0, &when, nullptr);
}

void handle(int signal, void (*handler)(int, siginfo_t*, void*), int flags) {
    struct sigaction action {};
    action.sa_sigaction = handler;
    action.sa_flags = SA_SIGINFO | SA_ONSTACK | flags;
    ::sigemptyset(&action.sa_mask);
    ::sigaction(signal, &action, nullptr);
}

// The last exception thrown on this thread and where, for simlab_thrown_from.
struct Thrown {
    const void* object = nullptr;
    Frames frames;
};
thread_local Thrown tThrown;

using CxaThrow = void (*)(void*, std::type_info*, void (*)(void*));

CxaThrow runtimeThrow() {
    static const CxaThrow real = reinterpret_cast<CxaThrow>(::dlsym(RTLD_NEXT, "__cxa_throw"));
    return real;
}

}  // namespace

void tellFailureSite(int signal) {
    Frames frames;
    walk(frames);
    if (frames.count == 0) return;
    Line line;
    line.add("{\"event\":\"crash\",\"signal\":");
    line.add(static_cast<std::uint64_t>(signal));
    line.add(",");
    line.frames(frames);
    line.send();
}

void endAs(int signal) {
    struct sigaction plain {};
    plain.sa_handler = SIG_DFL;
    ::sigemptyset(&plain.sa_mask);
    ::sigaction(signal, &plain, nullptr);
    sigset_t only;
    ::sigemptyset(&only);
    ::sigaddset(&only, signal);
    ::sigprocmask(SIG_UNBLOCK, &only, nullptr);
    ::syscall(SYS_tgkill, ::getpid(), ::syscall(SYS_gettid), signal);
}

void watchFailureSites(const char* probe) {
    if (std::strlen(probe) >= sizeof gProbe || !runtimeThrow()) return;
    std::strcpy(gProbe, probe);
    // A stack for the handlers, should the thread's own have overflowed (endless recursion).
    void* stack = ::mmap(nullptr, kAlternateStack, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (stack != MAP_FAILED) {
        stack_t alternate {};
        alternate.ss_sp = stack;
        alternate.ss_size = kAlternateStack;
        ::sigaltstack(&alternate, nullptr);
    }
    gWatching = true;
    Frames warm;  // the unwinder's one-time set-up, here rather than in a handler
    walk(warm);
    // A fault may come back while its handler walks (a stack the student's code broke): SA_NODEFER lets it in, to end
    // the walk.
    for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGABRT}) {
        handle(signal, onFatalSignal, SA_NODEFER);
    }
    handle(kSampleSignal, onSample, SA_RESTART);
    startSampler();
}

}  // namespace simlab::isolation::host

// The throw hook: the host exports __cxa_throw, so every throw in the process (the student's, the C++ library's,
// Simbody's) comes here first; where it was thrown is kept for the probe's course code, which asks with the object
// it caught (simlab_thrown_from); then the C++ runtime's own throw. The name is the C++ ABI's, which the hook must
// take.
// NOLINTNEXTLINE(bugprone-reserved-identifier)
extern "C" __attribute__((visibility("default"), noreturn)) void __cxa_throw(void* object, std::type_info* type,
                                                                            void (*destroy)(void*)) {
    using namespace simlab::isolation::host;
    if (gWatching) {
        tThrown.object = nullptr;
        walk(tThrown.frames);
        tThrown.object = object;
    }
    const CxaThrow real = runtimeThrow();
    if (!real) std::abort();
    real(object, type, destroy);
    __builtin_unreachable();
}

extern "C" __attribute__((visibility("default"))) int simlab_thrown_from(const void* object, std::uint64_t* at,
                                                                         int capacity) {
    using namespace simlab::isolation::host;
    if (!object || !at || tThrown.object != object) return 0;
    const int count = std::min(std::max(capacity, 0), tThrown.frames.count);
    std::copy(tThrown.frames.at, tThrown.frames.at + count, at);
    return count;
}
