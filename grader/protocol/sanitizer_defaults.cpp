// AddressSanitizer's defaults in the programs simlab runs in a sandbox, the judge and the probe's host: in a build
// with -DSIMLAB_SANITIZE=ON only (elsewhere this file is empty).
//
// A crash of student code must reach simlab as the signal it is (SIGSEGV, SIGFPE, ...), which the engine turns into
// "crashed (SIGSEGV)", so AddressSanitizer leaves those signals alone. Its leak check needs ptrace, which the
// sandbox's system-call filter refuses, so it is off here; the unit tests, outside any sandbox, keep it. The
// environment (ASAN_OPTIONS) would override these, but the sandbox passes the processes none.
#if defined(__SANITIZE_ADDRESS__)
#define SIMLAB_ASAN_DEFAULTS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SIMLAB_ASAN_DEFAULTS 1  // clang's spelling of it
#endif
#endif
#if defined(SIMLAB_ASAN_DEFAULTS)
extern "C" __attribute__((visibility("default"), used)) const char* __asan_default_options() {
    return "handle_segv=0:handle_sigbus=0:handle_sigfpe=0:handle_sigill=0:detect_leaks=0";
}
#endif
