// A student's compiled object, read by the object check before it is linked (isolation/elf.cpp, object_check.cpp):
// its bytes are the student's to shape (inline assembly, .incbin). Every name it holds is demangled and made
// printable as a refusal would show it; then the whole check runs on it, and the readers of archives and shared
// libraries (readElfFile tells them apart by content) take it too.
#include "fuzz.h"
#include "simlab/common/text.h"
#include "simlab/isolation/elf.h"
#include "simlab/isolation/object_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::isolation;
    const std::string bytes = simlab::fuzz::text(data, size);
    try {
        const ElfObject object = readElfObjectFromMemory(bytes, "NewtonsApple.o");
        for (const auto* list : {&object.defined, &object.undefined}) {
            for (const ElfSymbol& s : *list) simlab::engine::printable(demangle(s.name));
        }
        for (const std::string& name : object.ifuncs) simlab::engine::printable(demangle(name));
    } catch (const std::runtime_error&) {
    }
    const std::string path = simlab::fuzz::scratch().fresh() + "/NewtonsApple.o";
    simlab::fuzz::write(path, bytes);
    CourseSymbols course;
    course["main"] = {true, true, true, false, false, true, "course"};
    course["_Z13describeModelv"] = {true, true, true, false, false, true, "course"};
    course["_Z10buildModelv"] = {false, false, false, false, true, true, "course"};
    course["__gmon_start__"] = {false, false, false, false, false, true, "libc.so.6"};
    try {
        forbiddenCode(path, "NewtonsApple.cpp", course);
    } catch (const std::runtime_error&) {
    }
    try {
        readElfFile(path);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
