// simlab lock: simlab's places closed to other users but what a test is lent; simlab clean: what runs stopped for
// good left behind.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.h"
#include "simlab/build/lab.h"
#include "simlab/build/lock.h"
#include "simlab/build/manifest.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"

namespace simlab::cli {

void sayLeftovers(const std::vector<std::string>& removed) {
    if (removed.empty()) return;
    std::string names;
    for (std::size_t i = 0; i < removed.size() && i < 3; ++i) names += (i ? ", " : "") + engine::printable(removed[i]);
    if (removed.size() > 3) names += " and " + std::to_string(removed.size() - 3) + " more";
    std::cerr << "simlab: removed " << removed.size() << (removed.size() == 1 ? " folder" : " folders")
              << " that a stopped run of simlab left behind: " << names << "\n";
}

void addLock(CLI::App& app) {
    auto more = std::make_shared<std::vector<std::string>>();
    CLI::App* lock = app.add_subcommand(
        "lock",
        "Close simlab's places to other users - the course's sources, build or installation, its cache, and each "
        "FOLDER named (a lab's folder with its build, a class, its grades) - leaving them only what a test's tools "
        "are lent (the contracts, the precompiled headers, the course's objects, the probe's host) and the folders on "
        "the way to it. Where neither bubblewrap nor Landlock runs, this is what lets hidden tests run. Changes the "
        "modes others have, never the group's.");
    lock->add_option("folders", *more, "a lab's folder, a class's folder or a grades folder to close too");
    lock->callback([more] {
        const engine::Manifest manifest = engine::loadManifest();
        const engine::LockSummary summary = engine::lockPlaces(manifest, *more);
        std::string places;
        for (const std::string& p : summary.places) places += (places.empty() ? "" : ", ") + engine::printable(p);
        std::printf("simlab lock: %zu files and folders closed to other users under %s and the course's places; "
                    "%zu left to the tools as lent\n",
                    summary.closed, places.c_str(), summary.lent);
    });
    CLI::App* clean = app.add_subcommand(
        "clean", "Remove the folders runs of simlab that were stopped for good (killed, a power cut) left in $TMPDIR "
                 "or /tmp. simlab grade and check do it as they start; folders of a run still going are kept.");
    clean->callback([] {
        const std::vector<std::string> removed = engine::sweepLeftovers();
        sayLeftovers(removed);
        if (removed.empty()) std::printf("simlab clean: nothing left behind\n");
    });
}

}  // namespace simlab::cli
