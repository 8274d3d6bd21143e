// Where in the student's file a test failed: the frames a probe's process told (simlab/isolation/failure_sites.h),
// looked up in line tables. A probe is built without them (they would cost every check a tenth of its time); the
// first failure that needs a place builds its twin with them: the same file compiled with -g1 and linked the same way
// (cached, as objects are), used only if the student's code in it is the graded object's to the byte. Line tables
// change where the linker puts things, not the code, so each address is taken to the same place of the same
// function in the twin. The lookup is addr2line's, run in the sandbox as a tool on that file, so nothing of the
// student's runs again and no table the student's code could have shaped is read outside the sandbox. What it says
// is read as data too: only a frame in the student's own file, at a line the file has, is named.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace simlab::engine {

/// The addresses a probe's event told ("at"), innermost first, read as data: at most kMaxFailureFrames whole
/// numbers below kMaxFailureAddress; none at all if the list is anything else.
std::vector<std::uint64_t> readFailureFrames(const nlohmann::json& at);

/// One frame of addr2line's answer: the function as it demangles it, and the file and line (0: unknown).
struct LineEntry {
    std::string function, file;
    int line = 0;
};

/// addr2line's answer to -f -C -i -a: each address's frames, innermost first (calls inlined into it before it).
std::map<std::uint64_t, std::vector<LineEntry>> readAddr2line(const std::string& output);

/// The name a reason shows of a demangled function: "simulate" for "simulate(apple::Model&)", "Handler::handleEvent"
/// for "Handler::handleEvent(SimTK::State&, double, bool&) const", the function a lambda is in for the lambda, no
/// return type or "(anonymous namespace)::". Empty for what is not the name of a C++ function.
std::string functionShown(const std::string& demangled);

/// A frame in the student's file: "simulate() (NewtonsApple.cpp:52)"; `function` empty where its name cannot be
/// shown ("(NewtonsApple.cpp:52)").
struct SourceSite {
    std::string function;
    std::string file;
    int line = 0;
    bool found() const { return line > 0; }
    /// " in simulate() (NewtonsApple.cpp:52)", " (NewtonsApple.cpp:52)", or "" when not found: what a reason adds
    /// after its outcome.
    std::string inReason() const;
};

/// The innermost frame of `frames` in the file `file` (a name, as the student handed it in) of `lines` lines, by
/// addr2line's answers `entries`; not found if there is none.
SourceSite innermostIn(const std::vector<std::uint64_t>& frames,
                       const std::map<std::uint64_t, std::vector<LineEntry>>& entries, const std::string& file,
                       std::size_t lines);

/// Whether two relocatable objects (their bytes) hold the same code: the same executable sections, to the byte, with
/// the same relocations (places, kinds and addends). False for anything that is not a 64-bit ELF file whose section
/// table lies within it, or that holds no code.
bool sameCode(const std::string& oneObject, const std::string& otherObject);

/// Where each of `addresses` in the linked file `linked` (its bytes) lies in `twin`, linked from the same code: at
/// the same place in the function of the same name (and, of several, the same one by address) and size. An address
/// in no function, or in one the twin does not hold alike, is left out.
std::map<std::uint64_t, std::uint64_t> sameFunctionAddresses(const std::vector<std::uint64_t>& addresses,
                                                             const std::string& linked, const std::string& twin);

/// A submission's probe and its student's file, for looking failures up. Safe from several threads at once (a
/// submission's judges).
class FailureSites {
public:
    /// The probe's twin with line tables and the student's object in it; empty paths if it could not be made.
    struct LinedTwin {
        std::string probe, object;
    };
    /// Makes the twin in `folder` (a folder of simlab's).
    using BuildLined = std::function<LinedTwin(const std::string& folder)>;

    /// `probe`: the submission's probe, and `object` the student's object in it; `file` and `lines`: the student's
    /// file's name and its number of lines; `folder`: a folder of simlab's for the twin and the tool, made when a
    /// lookup first needs it.
    FailureSites(std::string probe, std::string object, std::string file, std::size_t lines, std::string folder,
                 BuildLined buildLined);

    /// Looks every address of `frameLists` up at once: the twin built the first time, then one run of addr2line in
    /// the sandbox (none if there is nothing new to look up, no addr2line, or no twin of the same code). What it
    /// cannot say stays unknown.
    void lookUp(const std::vector<std::vector<std::uint64_t>>& frameLists);

    /// The innermost frame of `frames` in the student's file, from what lookUp found.
    SourceSite site(const std::vector<std::uint64_t>& frames) const;

private:
    std::string probe_, object_, file_, folder_;
    std::size_t lines_ = 0;
    BuildLined buildLined_;
    bool twinTried_ = false;
    std::string twin_;  // the probe with line tables, once made and found to hold the same code
    std::map<std::uint64_t, std::vector<LineEntry>> entries_;
    mutable std::mutex lock_;
};

}  // namespace simlab::engine
