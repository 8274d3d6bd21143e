// Where in the student's file a test failed (failure_sites.h): the probe's frames, looked up by addr2line in the
// sandbox.
#include "simlab/grading/failure_sites.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
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

FailureSites::FailureSites(std::string probe, std::string file, std::size_t lines, std::string folder)
    : probe_(std::move(probe)), file_(std::move(file)), folder_(std::move(folder)), lines_(lines) {}

void FailureSites::lookUp(const std::vector<std::vector<std::uint64_t>>& frameLists) {
    std::vector<std::uint64_t> addresses;
    for (const auto& frames : frameLists) {
        for (const std::uint64_t address : frames) {
            if (!entries_.count(address)) addresses.push_back(address);
        }
    }
    std::sort(addresses.begin(), addresses.end());
    addresses.erase(std::unique(addresses.begin(), addresses.end()), addresses.end());
    if (addresses.empty() || file_.empty() || !fs::exists(kAddr2line)) return;
    // The tool's own copy of the probe, in a folder its user is handed for the run.
    createPrivateFolder(folder_);
    writeFileAtomically(folder_ + "/probe.so", readFile(probe_));
    isolation::ProcessRequest r;
    r.argv = {kAddr2line, "-e", "probe.so", "-f", "-C", "-i", "-a"};
    for (const std::uint64_t address : addresses) {
        char text[24];
        std::snprintf(text, sizeof text, "0x%llx", static_cast<unsigned long long>(address));
        r.argv.push_back(text);
    }
    r.env = {"PATH=/usr/bin:/bin", "HOME=" + folder_, "TMPDIR=/tmp", "LC_ALL=C"};
    r.workDir = folder_;
    r.limits = lookupLimits();
    r.keepOutput = 1 << 20;
    r.isolate = true;
    const isolation::ProcessResult run = isolation::runProcess(r);
    std::error_code ignored;
    fs::remove(folder_ + "/probe.so", ignored);
    if (!run.exitedCleanly()) return;  // a place is a help, never a reason to fail
    for (auto& [address, frames] : readAddr2line(run.output)) {
        if (std::binary_search(addresses.begin(), addresses.end(), address)) entries_[address] = std::move(frames);
    }
}

SourceSite FailureSites::site(const std::vector<std::uint64_t>& frames) const {
    return innermostIn(frames, entries_, file_, lines_);
}

}  // namespace simlab::engine
