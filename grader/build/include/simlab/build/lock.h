// simlab lock: simlab's places closed to other users, but what a grading's tools are lent. Where neither bubblewrap
// nor Landlock can run (limits only), files are kept from a test's throwaway user by their modes alone, and simlab
// runs hidden tests only once nothing else of its places opens for such a user (grading/grade.h, placesExposed).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "simlab/build/manifest.h"

namespace simlab::engine {

/// Everything of simlab's places any grading's tools are lent (lentToTools): the course's assignments', and every
/// lab's built in this simlab's cache. What limits only lets a throwaway user read of the places, and nothing more.
std::vector<std::string> lentOfPlaces(const Manifest& manifest);

struct LockSummary {
    std::vector<std::string> places;  ///< the places closed, each as named
    std::size_t closed = 0;           ///< files and folders others may no longer read, list or write
    std::size_t lent = 0;             ///< files and folders left readable for the tools (and folders passable)
};

/// Closes to other users (their mode bits alone: the group's are left as they are, and so a staff's group keeps
/// its reach) the course's places (its sources, build or installation, its cache, the sample class) and each of
/// `more` (a lab's folder with its build, a class, its grades): every file and folder under them but what
/// lentOfPlaces names, which others may read (folders: list and pass), and the folders on the way to it, which they
/// may pass alone. Links are not followed. Throws UsageError naming the first file it could not close (a read-only
/// file system, another user's file) and why; what it closed before stays closed.
LockSummary lockPlaces(const Manifest& manifest, const std::vector<std::string>& more);

}  // namespace simlab::engine
