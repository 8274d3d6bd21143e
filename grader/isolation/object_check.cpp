#include "simlab/isolation/object_check.h"

#include <algorithm>
#include <set>

#include "simlab/common/text.h"
#include "simlab/isolation/elf.h"

namespace simlab::isolation {

using engine::printable;

namespace {

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

std::string shortened(std::string text, std::size_t most) {
    if (text.size() > most) text = text.substr(0, most - 3) + "...";
    return text;
}

// The global operator new, new[], delete and delete[] in any of their forms (a class's own are nested names,
// _ZN...nwEm, and stay a student's to write).
bool replacesAllocation(const std::string& mangled) {
    for (const char* prefix : {"_Znw", "_Zna", "_Zdl", "_Zda"}) {
        if (startsWith(mangled, prefix)) return true;
    }
    return false;
}

// The sections g++ and clang++ make from C++ (and their relocations; .llvm_addrsig is clang's list of functions
// whose addresses are taken): anything else came from assembly the student wrote.
bool isCompilerSection(std::string name) {
    if (startsWith(name, ".rela.")) name = name.substr(5);
    static const std::set<std::string> exact = {
        "", ".text", ".data", ".bss", ".rodata", ".comment", ".eh_frame", ".init_array", ".fini_array",
        ".note.GNU-stack", ".note.gnu.property", ".group", ".shstrtab", ".strtab", ".symtab", ".symtab_shndx",
        ".gcc_except_table", ".tbss", ".tdata", ".data.rel.ro", ".data.rel", ".llvm_addrsig"};
    if (exact.count(name)) return true;
    for (const char* prefix : {".text.", ".data.", ".bss.", ".rodata.", ".gcc_except_table.", ".tbss.", ".tdata."}) {
        if (startsWith(name, prefix)) return true;
    }
    return false;
}

std::string sectionProblem(const std::string& section) {
    if (startsWith(section, ".preinit_array")) return "puts code in .preinit_array, which would run before the course's code";
    if (startsWith(section, ".init_array.") || startsWith(section, ".ctors")) {
        return "has a constructor with a priority (constructor(N) or init_priority(N)), which would run before the "
               "course's code; give it none";
    }
    if (startsWith(section, ".fini_array.") || startsWith(section, ".dtors")) {
        return "has a destructor with a priority (destructor(N)), which would run after the course's code ends";
    }
    if (section == ".init" || section == ".fini") {
        return "puts code in the " + section + " section, which runs outside the course's control";
    }
    if (startsWith(section, ".gnu.lto")) {
        return "holds link-time-optimization code (" + section + "), which the linker would compile outside the "
               "checks: write C++, not its assembly";
    }
    return "holds a section named " + section + ", which a C++ compiler does not make: the course links only "
           "compiled C++";
}

}  // namespace

std::vector<std::string> forbiddenCode(const std::string& objectPath, const std::string& sourceName,
                                       const CourseSymbols& course) {
    const ElfObject object = readElfObject(objectPath);
    std::vector<std::string> problems;
    auto say = [&](const std::string& what) {
        const std::string line = sourceName + " " + what;
        if (std::find(problems.begin(), problems.end(), line) == problems.end()) problems.push_back(line);
    };
    for (const std::string& section : object.sectionNames) {
        if (!isCompilerSection(section)) say(sectionProblem(printable(section)));
    }
    for (const std::string& ifunc : object.ifuncs) {
        say("defines " + shortened(printable(demangle(ifunc)), 160) +
            " as an ifunc, whose resolver would run before the course's code");
    }
    for (const ElfSymbol& symbol : object.defined) {
        const std::string name = shortened(printable(demangle(symbol.name)), 160);
        if (replacesAllocation(symbol.name)) {
            say("replaces the global " + name + ", which the course's code calls too: a submission allocates with "
                "new and delete as they are");
        }
        if (startsWith(symbol.name, "__gnu_lto")) say("holds link-time-optimization code (" + name + ")");
        if (symbol.name == "main") {
            say("defines main, which the course's code defines (the lab program's): a submission may define only the "
                "contract's functions and its own helpers");
            continue;
        }
        const auto found = course.find(symbol.name);
        if (found == course.end()) continue;
        const CourseSymbol& c = found->second;
        const std::string owner = c.from == "course" ? "the course's code" : c.from;
        if (!c.defined) {
            // Nothing of the course's defines it but something calls it: a contract function (which the course's
            // objects need), or a hook the runtime would call because it exists.
            if (!c.required) say("defines " + name + ", which the course's runtime would call as a hook");
            continue;
        }
        // A weak definition outside an inline function's group is as good as strong: the linker would keep it.
        if (symbol.strong || !symbol.comdat) {
            say("defines " + name + ", which " + owner +
                " defines: a submission may define only the contract's functions and its own helpers");
        } else if (c.strong && c.inObjects) {
            // Harmless (the course's out-of-line definition is the one linked), but never what a student means.
            say("redefines " + name + " inline, which " + owner + " defines");
        }
        // An inline copy of a library's function is harmless: the probe exports nothing it defines (the manifest's
        // probe_link), so a library's calls stay with the library, and the copy is the student's own process's.
    }
    return problems;
}

}  // namespace simlab::isolation
