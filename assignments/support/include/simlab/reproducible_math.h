// The same figures on every x86-64 machine.
//
// glibc's libm picks, when a program starts, one of several versions of sin, cos, exp, log, pow, atan2 and their
// kin by the processor's features: one built for FMA (fused multiply-add, on most processors since 2013), one for
// AMD's older FMA4, and one for plain SSE2. They round differently in the last bit for some arguments, so the same
// binary with the same input printed different digits on machines with and without FMA, and a chaotic run (the
// baby boot) drifts apart from there. The tunable below masks FMA and FMA4, so that every process of simlab's
// takes the SSE2 versions, which every x86-64 processor runs and which give the same bits everywhere.
//
// simlab passes it to everything it starts; a program a student runs from the shell (a lab program, a study
// program) starts itself again with it, once, before doing anything else. SIMLAB_NATIVE_MATH=1 keeps the
// processor's own versions (faster by a few percent, and digits that may differ from the handouts in the last
// place).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__x86_64__) && defined(__GLIBC__) && __has_include(<sys/platform/x86.h>)
// glibc's header spells C's _Bool, which GCC reads in C++ and clang does not: for clang it is bool, in this header.
#if defined(__clang__) && !defined(_Bool)
#define _Bool bool
#define SIMLAB_BOOL_FOR_GLIBC 1
#endif
#include <sys/platform/x86.h>
#ifdef SIMLAB_BOOL_FOR_GLIBC
#undef _Bool
#undef SIMLAB_BOOL_FOR_GLIBC
#endif
#define SIMLAB_MASKABLE_MATH 1
#endif

namespace simlab {

/// The glibc tunable that masks the processor features libm chooses its code by.
inline constexpr const char* kReproducibleMathTunable = "glibc.cpu.hwcaps=-FMA,-FMA4";

/// GLIBC_TUNABLES with the mask added to `current` (which may be null or hold other tunables).
inline std::string reproducibleMathTunables(const char* current) {
    const std::string now = current ? current : "";
    if (now.find(kReproducibleMathTunable) != std::string::npos) return now;
    return now.empty() ? kReproducibleMathTunable : now + ":" + kReproducibleMathTunable;
}

/// Whether libm runs its FMA or FMA4 versions in this process (the mask did not reach it).
inline bool nativeMathActive() {
#ifdef SIMLAB_MASKABLE_MATH
    return CPU_FEATURE_ACTIVE(FMA) || CPU_FEATURE_ACTIVE(FMA4);
#else
    return false;
#endif
}

/// Call first in main: if libm chose the processor's own versions, start this program again (same arguments,
/// same process) with the mask in GLIBC_TUNABLES. Does nothing when they are already the reproducible ones, when
/// SIMLAB_NATIVE_MATH=1, or when starting again fails (the program then runs on, with the processor's versions).
inline void useReproducibleMath(char** argv) {
    if (!nativeMathActive()) {
        ::unsetenv("SIMLAB_REPRODUCIBLE_MATH_TRIED");
        return;
    }
    const char* native = std::getenv("SIMLAB_NATIVE_MATH");
    if (native && std::strcmp(native, "1") == 0) return;
    // Once only: a glibc that ignores the tunable would otherwise start the program forever.
    if (std::getenv("SIMLAB_REPRODUCIBLE_MATH_TRIED")) return;
    const std::string tunables = reproducibleMathTunables(std::getenv("GLIBC_TUNABLES"));
    if (::setenv("GLIBC_TUNABLES", tunables.c_str(), 1) != 0 || ::setenv("SIMLAB_REPRODUCIBLE_MATH_TRIED", "1", 1) != 0) {
        return;
    }
    ::execv("/proc/self/exe", argv);
    ::unsetenv("SIMLAB_REPRODUCIBLE_MATH_TRIED");
}

}  // namespace simlab
