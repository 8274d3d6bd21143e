// Reading ELF files: what a compiled object, a static archive or a shared library defines. The grader uses it
// to check a student's object before linking it (object_check.h): the object comes from untrusted
// source, inline assembly included, so every offset and size is checked against the file.
#pragma once

#include <string>
#include <vector>

namespace simlab::isolation {

struct ElfSymbol {
    std::string name;       ///< as linked (mangled), without a "@VERSION" suffix
    bool strong = false;    ///< a global definition; weak and unique ones are not
    bool comdat = false;    ///< in a section of a COMDAT group: an inline function's or template's copy
    bool ifunc = false;     ///< STT_GNU_IFUNC: its resolver runs while the program is loaded
    bool exported = false;  ///< default or protected visibility: it can be exported, and so interpose
};

struct ElfObject {
    std::vector<ElfSymbol> defined;         ///< global, weak and unique symbols defined here
    std::vector<ElfSymbol> undefined;       ///< global and weak symbols referred to but not defined here
    std::vector<std::string> sectionNames;  ///< every section's name (relocatable objects only)
    std::vector<std::string> ifuncs;        ///< every symbol typed STT_GNU_IFUNC, whatever its binding (a local
                                            ///< one too: the loader runs its resolver all the same)
};

/// A relocatable object (.o): its symbol table and sections. Throws std::runtime_error("<path>: <what>") for a
/// file that is not a 64-bit little-endian ELF object or is malformed.
ElfObject readElfObject(const std::string& path);
ElfObject readElfObjectFromMemory(const std::string& bytes, const std::string& nameForErrors);
/// A shared library (.so): its dynamic symbol table's definitions.
ElfObject readSharedLibrary(const std::string& path);
/// A static archive (.a): every member that is a relocatable object, merged.
ElfObject readArchive(const std::string& path);
/// Any of the three, told apart by content. Throws for anything else (a linker script, say).
ElfObject readElfFile(const std::string& path);

/// "simlab::describeModel(...)" for its mangled name; a name that does not demangle comes back unchanged, and so
/// does one whose demangled text could grow past bounds (over 1 KiB, or more than 12 substitutions).
std::string demangle(const std::string& name);

}  // namespace simlab::isolation
