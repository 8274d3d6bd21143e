// Reading ELF files: what g++ 12 makes of the definitions a student's object may or may not hold.
#include <catch2/catch.hpp>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>

#include "simlab/isolation/elf.h"
#include "simlab/common/files.h"

namespace elf_test {

using namespace simlab::engine;
using namespace simlab::isolation;

namespace {

// `source` compiled by g++ into an object, read back.
ElfObject compiled(const std::string& source) {
    static TempDir dir("simlab-elf-test-");
    static int count = 0;
    const std::string base = dir.path() + "/t" + std::to_string(++count);
    writeFileAtomically(base + ".cpp", source);
    const std::string command = "/usr/bin/g++ -std=c++17 -O1 -fPIE -c " + base + ".cpp -o " + base + ".o";
    REQUIRE(std::system(command.c_str()) == 0);
    return readElfObject(base + ".o");
}

const ElfSymbol* find(const ElfObject& o, const std::string& name) {
    const auto at = std::find_if(o.defined.begin(), o.defined.end(), [&](const ElfSymbol& s) { return s.name == name; });
    return at == o.defined.end() ? nullptr : &*at;
}

bool hasSection(const ElfObject& o, const std::string& name) {
    return std::find(o.sectionNames.begin(), o.sectionNames.end(), name) != o.sectionNames.end();
}

}  // namespace

TEST_CASE("a plain function is strong; an inline one is weak and in a COMDAT group", "[elf]") {
    const ElfObject o = compiled("int plain(int x) { return x + 1; }\n"
                                 "inline int shared(int x) { return x * 2; }\n"
                                 "int (*taken)(int) = shared;\n");
    const ElfSymbol* plain = find(o, "_Z5plaini");
    REQUIRE(plain);
    CHECK(plain->strong);
    CHECK_FALSE(plain->comdat);
    const ElfSymbol* shared = find(o, "_Z6sharedi");
    REQUIRE(shared);
    CHECK_FALSE(shared->strong);
    CHECK(shared->comdat);
}

TEST_CASE("an explicit specialization is strong; a weak attribute is weak but outside any group", "[elf]") {
    const ElfObject o = compiled("template <class T> int f(T x) { return int(x); }\n"
                                 "template <> int f<int>(int x) { return 7 * x; }\n"
                                 "__attribute__((weak)) int replaceable(int x) { return x; }\n");
    const ElfSymbol* special = find(o, "_Z1fIiEiT_");
    REQUIRE(special);
    CHECK(special->strong);
    const ElfSymbol* weak = find(o, "_Z11replaceablei");
    REQUIRE(weak);
    CHECK_FALSE(weak->strong);
    CHECK_FALSE(weak->comdat);
}

TEST_CASE("code that would run before main shows in the section names and symbol types", "[elf]") {
    // Each does something, or the optimizer drops it.
    const ElfObject o = compiled(
        "volatile int seen = 0;\n"
        "__attribute__((constructor(101))) void early() { seen = 1; }\n"
        "__attribute__((destructor(101))) void late() { seen = 2; }\n"
        "struct S { S() { seen = 3; } };\n"
        "__attribute__((init_priority(101))) S s;\n"
        "asm(\".section .preinit_array,\\\"aw\\\"\\n.quad 0\\n.previous\");\n"
        "extern \"C\" int impl() { return 1; }\n"
        "extern \"C\" int (*resolve())() { return impl; }\n"
        "extern \"C\" int chosen() __attribute__((ifunc(\"resolve\")));\n");
    CHECK(hasSection(o, ".init_array.00101"));
    CHECK(hasSection(o, ".fini_array.00101"));
    CHECK(hasSection(o, ".preinit_array"));
    const ElfSymbol* chosen = find(o, "chosen");
    REQUIRE(chosen);
    CHECK(chosen->ifunc);
}

TEST_CASE("shared libraries and archives give their definitions", "[elf]") {
    const ElfObject libm = readElfFile("/lib/x86_64-linux-gnu/libm.so.6");
    CHECK(find(libm, "cos"));
    CHECK(libm.sectionNames.empty());
    const ElfObject nonshared = readElfFile("/usr/lib/x86_64-linux-gnu/libc_nonshared.a");
    CHECK(find(nonshared, "atexit"));
}

TEST_CASE("what is not a well-formed ELF file is an error, never a crash", "[elf]") {
    TempDir dir("simlab-elf-bad-");
    const ElfObject good = compiled("int x = 1;\n");
    (void)good;
    writeFileAtomically(dir.path() + "/empty", "");
    writeFileAtomically(dir.path() + "/noise", std::string(4096, '\x7f'));
    CHECK_THROWS_AS(readElfFile(dir.path() + "/empty"), std::runtime_error);
    CHECK_THROWS_AS(readElfFile(dir.path() + "/noise"), std::runtime_error);
    // A real object cut short: its tables point past the end.
    std::string object = readFile("/usr/lib/x86_64-linux-gnu/crti.o");
    CHECK_THROWS_AS(readElfObjectFromMemory(object.substr(0, 200), "cut"), std::runtime_error);
    // Its section header table moved far away.
    object.replace(0x28, 8, std::string("\xff\xff\xff\xff\xff\xff\x00\x00", 8));
    CHECK_THROWS_AS(readElfObjectFromMemory(object, "moved"), std::runtime_error);
}

TEST_CASE("names demangle for messages", "[elf]") {
    CHECK(demangle("_ZN6simlab14accuracyDigitsEddd") == "simlab::accuracyDigits(double, double, double)");
    CHECK(demangle("main") == "main");
}

TEST_CASE("a name whose demangled text would grow past bounds stays mangled, and nothing is spent on it", "[elf]") {
    // Each level repeats the one before it twice (S_ S_, then S0_ S0_, S2_ S2_, ...: substitutions numbered in base
    // 36): demangled, 2 to the power of the levels.
    const auto base36 = [](int n) {
        const char digits[] = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";
        std::string text;
        do {
            text.insert(text.begin(), digits[n % 36]);
            n /= 36;
        } while (n > 0);
        return text;
    };
    std::string bomb = "_Z1f1AIiiE";
    for (int level = 0; level < 30; ++level) {
        const std::string s = level == 0 ? "S_" : "S" + base36(2 * level - 2) + "_";
        bomb += "1AI" + s + s + "E";
    }
    const auto start = std::chrono::steady_clock::now();
    CHECK(demangle(bomb) == bomb);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
    CHECK(demangle("_ZN6simlab13describeModelEv") == "simlab::describeModel()");
    CHECK(demangle("_ZNSt6vectorIdSaIdEE9push_backEOd") == "std::vector<double, std::allocator<double> >::push_back(double&&)");
}

}  // namespace elf_test
