// Where in the student's file a test failed (failure_sites.h): the probe's frames, looked up by addr2line in the
// sandbox.
#include "simlab/grading/failure_sites.h"

#include <elf.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string_view>

#include "simlab/common/files.h"
#include "simlab/isolation/failure_sites.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

// binutils' addr2line: it reads a file's line tables (DWARF 5, as clang and GCC write them) and runs nothing of it.
constexpr const char* kAddr2line = "/usr/bin/addr2line";

// A lookup is small: a probe's line tables, a few dozen addresses.
Limits lookupLimits() {
    Limits l;
    l.wallSeconds = 60;
    l.cpuSeconds = 20;
    l.memoryMiB = 1024;
    l.outputKiB = 1024;
    l.fileMiB = 16;
    l.processes = 4;
    return l;
}

bool isHexAddress(const std::string& line) {
    const auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
    return line.size() > 2 && line.size() <= 18 && line[0] == '0' && line[1] == 'x' &&
           std::all_of(line.begin() + 2, line.end(), hex);
}

// "file:line" or "file:line (discriminator 3)", as addr2line writes a frame's place; line 0 where unknown ("??:0",
// "file:?").
void readPlace(const std::string& text, LineEntry& entry) {
    std::string place = text;
    if (const std::size_t extra = place.find(" ("); extra != std::string::npos) place.erase(extra);
    const std::size_t colon = place.rfind(':');
    if (colon == std::string::npos) return;
    entry.file = place.substr(0, colon);
    const std::string number = place.substr(colon + 1);
    if (number.empty() || number.size() > 9 ||
        !std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return;
    }
    entry.line = std::stoi(number);
}

// An ELF file's section headers, read with every offset and size checked against the file; none for anything else.
class ElfSections {
public:
    explicit ElfSections(const std::string& file) : file_(file) {
        Elf64_Ehdr header;
        if (!within(0, sizeof header)) return;
        std::memcpy(&header, file.data(), sizeof header);
        if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64 ||
            header.e_shentsize != sizeof(Elf64_Shdr) || header.e_shnum == 0 || header.e_shstrndx >= header.e_shnum ||
            !within(header.e_shoff, std::uint64_t{header.e_shnum} * sizeof(Elf64_Shdr))) {
            return;
        }
        std::vector<Elf64_Shdr> all(header.e_shnum);
        std::memcpy(all.data(), file.data() + header.e_shoff, all.size() * sizeof(Elf64_Shdr));
        for (const Elf64_Shdr& s : all) {
            if (s.sh_type != SHT_NOBITS && !within(s.sh_offset, s.sh_size)) return;
        }
        names_ = all[header.e_shstrndx];
        list_ = std::move(all);
    }
    const std::vector<Elf64_Shdr>& list() const { return list_; }
    std::string contents(const Elf64_Shdr& s) const {
        return s.sh_type == SHT_NOBITS ? std::string() : file_.substr(s.sh_offset, s.sh_size);
    }
    /// The string at `offset` of the string table `table`; empty where there is none.
    std::string text(const Elf64_Shdr& table, std::uint64_t offset) const {
        if (offset >= table.sh_size) return "";
        const char* start = file_.data() + table.sh_offset + offset;
        return std::string(start, strnlen(start, table.sh_size - offset));
    }
    std::string name(const Elf64_Shdr& s) const { return text(names_, s.sh_name); }

private:
    bool within(std::uint64_t offset, std::uint64_t size) const {
        return offset <= file_.size() && size <= file_.size() - offset;
    }
    const std::string& file_;
    Elf64_Shdr names_{};
    std::vector<Elf64_Shdr> list_;
};

// A relocatable object's code: each executable section's name and bytes, and its relocations' places, kinds and
// addends (their symbols' numbers aside: line tables add symbols). Empty for what is not an ELF object.
std::vector<std::pair<std::string, std::string>> codeOf(const std::string& file) {
    const ElfSections sections(file);
    std::vector<std::pair<std::string, std::string>> code;
    const std::vector<Elf64_Shdr>& list = sections.list();
    for (const Elf64_Shdr& s : list) {
        if (s.sh_flags & SHF_EXECINSTR) code.emplace_back(sections.name(s), sections.contents(s));
        if (s.sh_type != SHT_RELA || s.sh_info >= list.size() || !(list[s.sh_info].sh_flags & SHF_EXECINSTR)) continue;
        const std::string entries = sections.contents(s);
        std::string relocations;
        for (std::size_t at = 0; at + sizeof(Elf64_Rela) <= entries.size(); at += sizeof(Elf64_Rela)) {
            Elf64_Rela r;
            std::memcpy(&r, entries.data() + at, sizeof r);
            relocations += std::to_string(r.r_offset) + " " + std::to_string(ELF64_R_TYPE(r.r_info)) + " " +
                           std::to_string(r.r_addend) + "\n";
        }
        code.emplace_back(sections.name(s), relocations);
    }
    return code;
}

// A linked file's functions, by their symbols: name, address and size, in the order of their addresses.
struct Function {
    std::string name;
    std::uint64_t address = 0, size = 0;
};
std::vector<Function> functionsOf(const std::string& file) {
    const ElfSections sections(file);
    std::vector<Function> functions;
    const std::vector<Elf64_Shdr>& list = sections.list();
    for (const Elf64_Shdr& s : list) {
        if (s.sh_type != SHT_SYMTAB || s.sh_link >= list.size()) continue;
        const std::string symbols = sections.contents(s);
        for (std::size_t at = 0; at + sizeof(Elf64_Sym) <= symbols.size(); at += sizeof(Elf64_Sym)) {
            Elf64_Sym sym;
            std::memcpy(&sym, symbols.data() + at, sizeof sym);
            if (ELF64_ST_TYPE(sym.st_info) != STT_FUNC || sym.st_shndx == SHN_UNDEF || sym.st_size == 0) continue;
            functions.push_back({sections.text(list[s.sh_link], sym.st_name), sym.st_value, sym.st_size});
        }
    }
    std::sort(functions.begin(), functions.end(), [](const Function& a, const Function& b) {
        return a.address != b.address ? a.address < b.address : a.name < b.name;
    });
    return functions;
}

// The characters a C++ function's shown name holds: identifiers, scopes, template arguments.
bool nameCharacter(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '<' || c == '>' || c == ',' ||
           c == ' ' || c == '*' || c == '&' || c == '~';
}

}  // namespace

std::vector<std::uint64_t> readFailureFrames(const nlohmann::json& at) {
    std::vector<std::uint64_t> frames;
    if (!at.is_array() || at.empty() || at.size() > static_cast<std::size_t>(isolation::kMaxFailureFrames)) return {};
    for (const nlohmann::json& address : at) {
        if (!address.is_number_unsigned()) return {};
        const std::uint64_t value = address.get<std::uint64_t>();
        if (value >= isolation::kMaxFailureAddress) return {};
        frames.push_back(value);
    }
    return frames;
}

std::map<std::uint64_t, std::vector<LineEntry>> readAddr2line(const std::string& output) {
    std::map<std::uint64_t, std::vector<LineEntry>> entries;
    std::istringstream lines(output);
    std::vector<LineEntry>* current = nullptr;
    std::string line, function;
    bool haveFunction = false;
    while (std::getline(lines, line)) {
        if (isHexAddress(line)) {
            current = &entries[std::stoull(line.substr(2), nullptr, 16)];
            haveFunction = false;
            continue;
        }
        if (!current) continue;
        if (!haveFunction) {
            function = line;
            haveFunction = true;
            continue;
        }
        LineEntry entry;
        entry.function = function == "??" ? "" : function;
        readPlace(line, entry);
        current->push_back(entry);
        haveFunction = false;
    }
    return entries;
}

std::string functionShown(const std::string& demangled) {
    std::string name = demangled;
    for (const std::string_view anonymous :
         {std::string_view("(anonymous namespace)::"), std::string_view("{anonymous}::")}) {
        for (std::size_t at = name.find(anonymous); at != std::string::npos; at = name.find(anonymous, at)) {
            name.erase(at, anonymous.size());
        }
    }
    // The name ends at its parameters: the first '(' outside template arguments that is not an operator's own.
    int depth = 0;
    std::size_t end = std::string::npos;
    for (std::size_t i = 0; i < name.size(); ++i) {
        const char c = name[i];
        if (name.compare(i, 10, "operator()") == 0) {
            i += 9;
            continue;
        }
        if (name.compare(i, 8, "operator") == 0 && i + 8 < name.size() && !nameCharacter(name[i + 8])) return "";
        if (c == '<') ++depth;
        if (c == '>') --depth;
        if (c == '(' && depth == 0) {
            end = i;
            break;
        }
    }
    if (end == std::string::npos || depth != 0) return "";
    name.erase(end);
    // A function template's demangled name starts with its return type: the name is after the last space outside
    // template arguments.
    depth = 0;
    std::size_t start = 0;
    for (std::size_t i = 0; i < name.size(); ++i) {
        if (name[i] == '<') ++depth;
        if (name[i] == '>') --depth;
        if (name[i] == ' ' && depth == 0) start = i + 1;
    }
    name.erase(0, start);
    std::string characters = name;  // a call operator's parentheses are the one kind a name may hold
    for (std::size_t at = characters.find("operator()"); at != std::string::npos; at = characters.find("operator()")) {
        characters.erase(at + 8, 2);
    }
    if (name.empty() || name.size() > 120 || !std::all_of(characters.begin(), characters.end(), nameCharacter)) {
        return "";
    }
    if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return "";
    return name;
}

std::string SourceSite::inReason() const {
    if (!found()) return "";
    const std::string place = "(" + file + ":" + std::to_string(line) + ")";
    return function.empty() ? " " + place : " in " + function + "() " + place;
}

SourceSite innermostIn(const std::vector<std::uint64_t>& frames,
                       const std::map<std::uint64_t, std::vector<LineEntry>>& entries, const std::string& file,
                       std::size_t lines) {
    for (const std::uint64_t address : frames) {
        const auto found = entries.find(address);
        if (found == entries.end()) continue;
        for (const LineEntry& entry : found->second) {
            if (fs::path(entry.file).filename().string() != file || entry.line < 1 ||
                static_cast<std::size_t>(entry.line) > lines) {
                continue;
            }
            SourceSite site;
            site.function = functionShown(entry.function);
            site.file = file;
            site.line = entry.line;
            return site;
        }
    }
    return {};
}

bool sameCode(const std::string& oneObject, const std::string& otherObject) {
    const auto one = codeOf(oneObject);
    return !one.empty() && one == codeOf(otherObject);
}

std::map<std::uint64_t, std::uint64_t> sameFunctionAddresses(const std::vector<std::uint64_t>& addresses,
                                                             const std::string& linked, const std::string& twin) {
    const std::vector<Function> from = functionsOf(linked), to = functionsOf(twin);
    // Each function by its name and its place among those of the same name (static functions of two files).
    auto place = [](const std::vector<Function>& functions, std::size_t i) {
        std::size_t before = 0;
        for (std::size_t j = 0; j < i; ++j) before += functions[j].name == functions[i].name;
        return before;
    };
    std::map<std::uint64_t, std::uint64_t> mapped;
    for (const std::uint64_t address : addresses) {
        std::size_t found = from.size();
        for (std::size_t i = 0; i < from.size(); ++i) {
            if (from[i].address <= address && address - from[i].address < from[i].size) found = i;
        }
        if (found == from.size()) continue;
        const Function& f = from[found];
        const std::size_t nth = place(from, found);
        for (std::size_t i = 0, seen = 0; i < to.size(); ++i) {
            if (to[i].name != f.name || seen++ != nth) continue;
            if (to[i].size == f.size) mapped[address] = to[i].address + (address - f.address);
            break;
        }
    }
    return mapped;
}

FailureSites::FailureSites(std::string probe, std::string object, std::string file, std::size_t lines,
                           std::string folder, BuildLined buildLined)
    : probe_(std::move(probe)), object_(std::move(object)), file_(std::move(file)), folder_(std::move(folder)),
      lines_(lines), buildLined_(std::move(buildLined)) {}

void FailureSites::lookUp(const std::vector<std::vector<std::uint64_t>>& frameLists) {
    std::lock_guard<std::mutex> guard(lock_);
    std::vector<std::uint64_t> addresses;
    for (const auto& frames : frameLists) {
        for (const std::uint64_t address : frames) {
            if (!entries_.count(address)) addresses.push_back(address);
        }
    }
    std::sort(addresses.begin(), addresses.end());
    addresses.erase(std::unique(addresses.begin(), addresses.end()), addresses.end());
    if (addresses.empty() || file_.empty() || !fs::exists(kAddr2line)) return;
    // The twin with line tables, once: used only if the student's object in it is the graded one's code, byte for
    // byte, relocation for relocation.
    if (!twinTried_) {
        twinTried_ = true;
        createPrivateFolder(folder_);
        const LinedTwin twin = buildLined_ ? buildLined_(folder_) : LinedTwin{};
        if (!twin.probe.empty() && !twin.object.empty() && sameCode(readFile(object_), readFile(twin.object))) {
            twin_ = twin.probe;
        }
    }
    if (twin_.empty()) return;
    // Each address as it lies in the twin: at the same place in the function of the same name and size.
    const std::map<std::uint64_t, std::uint64_t> inTwin =
        sameFunctionAddresses(addresses, readFile(probe_), readFile(twin_));
    if (inTwin.empty()) return;
    // The tool's own copy of the twin, in a folder its user is handed for the run.
    const std::string tool = folder_ + "/tool";
    createPrivateFolder(tool);
    writeFileAtomically(tool + "/probe.so", readFile(twin_));
    isolation::ProcessRequest r;
    r.argv = {kAddr2line, "-e", "probe.so", "-f", "-C", "-i", "-a"};
    std::map<std::uint64_t, std::uint64_t> fromTwin;
    for (const auto& [address, twinAddress] : inTwin) {
        char text[24];
        std::snprintf(text, sizeof text, "0x%llx", static_cast<unsigned long long>(twinAddress));
        r.argv.push_back(text);
        fromTwin[twinAddress] = address;
    }
    r.env = {"PATH=/usr/bin:/bin", "HOME=" + tool, "TMPDIR=/tmp", "LC_ALL=C"};
    r.workDir = tool;
    r.limits = lookupLimits();
    r.keepOutput = 1 << 20;
    r.isolate = true;
    const isolation::ProcessResult run = isolation::runProcess(r);
    std::error_code ignored;
    fs::remove_all(tool, ignored);
    if (!run.exitedCleanly()) return;  // a place is a help, never a reason to fail
    for (auto& [twinAddress, frames] : readAddr2line(run.output)) {
        const auto address = fromTwin.find(twinAddress);
        if (address != fromTwin.end()) entries_[address->second] = std::move(frames);
    }
}

SourceSite FailureSites::site(const std::vector<std::uint64_t>& frames) const {
    std::lock_guard<std::mutex> guard(lock_);
    return innermostIn(frames, entries_, file_, lines_);
}

}  // namespace simlab::engine
