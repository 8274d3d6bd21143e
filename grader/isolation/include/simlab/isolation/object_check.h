// The object check: what a student's compiled object may hold before it is linked into a probe or a program. The
// probe's design already keeps every line of the student's code away from privilege (it is loaded only by a test's
// own user: host/probe_host.cpp); the check keeps a submission to what C++ makes of one file, so that the course's
// code in the probe calls the course's functions and nothing the student put in their place, and so that each
// refusal is a reason a student can read rather than a surprise at run time.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace simlab::isolation {

/// A symbol the course's side of a probe defines or refers to - in its objects, the libraries it links or the C
/// and C++ runtime.
struct CourseSymbol {
    bool defined = false;     ///< somewhere in the course
    bool strong = false;      ///< some definition of it is strong (not weak or inline)
    bool inObjects = false;   ///< the course's objects define it (their copy is the one linked)
    bool inLibraries = false; ///< a shared library or the runtime defines it
    bool required = false;    ///< the course's objects need it and nothing of the course's defines it: a contract
                              ///< function the student writes
    bool referenced = false;  ///< something of the course's refers to it
    std::string from;         ///< where it is defined: "course", or a library's file name such as "libc.so.6"
};
using CourseSymbols = std::map<std::string, CourseSymbol>;

/// What a student's object may not do, one line each ("NewtonsApple.cpp defines simlab::describeModel(...), which
/// the course's code defines: a submission may define only the contract's functions and its own helpers"): hold
/// a section a compiler does not make from C++ (LTO code, .preinit_array, .init, a constructor or destructor with a
/// priority, ...), define an ifunc (local ones too), replace the global operator new or delete (inline or not),
/// define a symbol the course defines (or redefine inline one it defines out of line), or define a hook the
/// course's runtime calls when it exists (__gmon_start__, say). Empty when it is clean.
std::vector<std::string> forbiddenCode(const std::string& objectPath, const std::string& sourceName,
                                       const CourseSymbols& course);

}  // namespace simlab::isolation
