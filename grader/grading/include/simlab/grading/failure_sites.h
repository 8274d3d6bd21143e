// Where in the student's file a test failed: the frames a probe's process told (simlab/isolation/failure_sites.h),
// looked up in the probe's line tables. The student's file is compiled with line tables for this (the build's
// compile command); the lookup is addr2line's, run in the sandbox as a tool on the probe as a file, so nothing of the
// student's runs again and no table the student's code could have shaped is read outside the sandbox. What it says is
// read as data too: only a frame in the student's own file, at a line the file has, is named.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
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

/// A submission's probe and its student's file, for looking failures up.
class FailureSites {
public:
    /// `probe`: the submission's probe; `file` and `lines`: the student's file's name and its number of lines;
    /// `folder`: a folder of simlab's, made when a lookup needs it, for the tool's copy of the probe.
    FailureSites(std::string probe, std::string file, std::size_t lines, std::string folder);

    /// Looks every address of `frameLists` up at once: one run of addr2line in the sandbox (none if there is
    /// nothing to look up, or no addr2line). What it cannot say stays unknown.
    void lookUp(const std::vector<std::vector<std::uint64_t>>& frameLists);

    /// The innermost frame of `frames` in the student's file, from what lookUp found.
    SourceSite site(const std::vector<std::uint64_t>& frames) const;

private:
    std::string probe_, file_, folder_;
    std::size_t lines_ = 0;
    std::map<std::uint64_t, std::vector<LineEntry>> entries_;
};

}  // namespace simlab::engine
