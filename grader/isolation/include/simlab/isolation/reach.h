// What a sandboxed process may read: one declaration, which each mode of the sandbox enforces in its own way.
//
//   the system         its programs and libraries (systemFolders, less /usr/local: notTheSystems), the loader's
//                      cache, Debian's alternatives, the fonts and the time zone (systemFiles), and the harmless
//                      devices (systemDevices);
//   what it is lent    ProcessRequest::readOnlyPaths: a compile its contract and precompiled header, a link the
//                      course's objects, a probe its copy of the probe and its host, a judge its own copy;
//   its own folder     ProcessRequest::workDir (a probe's test: the folder its server makes for it).
//
// Nothing else. In particular nothing under simlab's places (addPlaces), wherever they lie, the system's folders
// included: the course's sources and build (its ccache too), an installation's lib/simlab and share/simlab, every
// lab's folder (its history, corpus and solution) and build, the caches, a class and its grades.
//
//   bubblewrap    binds the system and what is lent, nothing else; a place among the system's folders is covered
//                 by an empty stand-in;
//   Landlock      grants read rights on the system and what is lent, nothing else: a place among the system's
//                 folders is carved out of their rights (a lab under /usr gets no right through /usr);
//   limits only   cannot hide a file by namespace. Files are kept apart by their modes, so before hidden tests
//                 run, exposedPlaces tries every file under the places as a throwaway user would, and simlab refuses
//                 while any that is not lent opens (`simlab lock` closes them).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace simlab::isolation {

/// The system's folders every sandboxed process reads and runs from: /usr, /bin, /sbin, /lib and its kin.
const std::vector<std::string>& systemFolders();
/// The system's files outside those folders it reads: the loader's cache, Debian's alternatives (BLAS and LAPACK,
/// which Simbody loads, are chosen there), the fonts (gnuplot, in a judge) and the time zone.
const std::vector<std::string>& systemFiles();
/// What lies among the system's folders and is not the system's: /usr/local, the machine's own additions (another
/// course's lab, a tree installed from source), which no sandbox shows but what it lends from there.
const std::vector<std::string>& notTheSystems();
/// simlab's places and notTheSystems(): what bubblewrap covers and Landlock carves out of the system's folders.
std::vector<std::string> outOfReach();
/// The devices it may read and write: /dev/null, /dev/zero, /dev/urandom, /dev/random.
const std::vector<std::string>& systemDevices();

/// simlab's places, added to those before (relative paths are taken from the working directory): nothing under
/// them is any sandboxed process's to read but what it is lent. The engine adds its sources, build, installation
/// and caches when it reads its manifest, a lab's folder and build when it builds the lab, and a class's folder
/// and its grades when it grades them. A system folder itself, or a folder that holds one, is never a place.
void addPlaces(const std::vector<std::string>& paths);
/// The places so far, each an absolute, normal path (and, where a link leads elsewhere, the path it leads to).
std::vector<std::string> places();
/// The place that holds `path` (itself, or a folder above it), or "" for none.
std::string placeOf(const std::string& path);

/// Whether every sandbox shows `path` without lending it: inside a system folder and under no place.
bool visibleInSandboxes(const std::string& path);

/// Whether a process lent `lent` and working in `workDir` may read `path`: the system (less the places), what
/// it is lent (a folder with all that is in it), its own folder, and nothing else. The declaration the walks of
/// the isolation's tests check every readable file against.
bool withinReach(const std::string& path, const std::vector<std::string>& lent, const std::string& workDir);

/// What of simlab's places a throwaway user can read here, tried before hidden tests run where files are kept
/// apart by their modes alone (limits only): every regular file under every place, opened as a user never used
/// before, with no group and no capability (as root), or as the calling user (not as root). As root, nothing below
/// a folder others may not pass through is walked: no such user reaches it.
struct Exposure {
    std::vector<std::string> readable;  ///< files that opened, not lent, by name
    std::size_t readableCount = 0;      ///< how many
    std::size_t tried = 0;              ///< the files tried
    bool bounded = false;               ///< the places hold more than the walk's bound (500,000 entries) that
                                        ///< others may reach: the rest were not tried, and the places count as
                                        ///< exposed
    std::string boundedIn;              ///< the place the walk was in when it reached its bound
    std::vector<std::string> passable;  ///< places with nothing lent below them that such a user may pass
                                        ///< through: what simlab writes there later would be readable
    std::string error;                  ///< why nothing could be tried ("" when it was)
    bool exposed() const { return readableCount > 0 || !passable.empty() || bounded || !error.empty(); }
};
/// Every file under the places, less `lent` (files or folders, with what is in them), tried as above; and each
/// place with nothing lent below it, tried for passage.
Exposure exposedPlaces(const std::vector<std::string>& lent);

}  // namespace simlab::isolation
