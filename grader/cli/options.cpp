// What several simlab commands share: limit options checked against the rubric's ranges, and a student's file
// read from the command line the way grading reads it; the cores to use by default; the hand-over to a program.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <thread>

#include "commands.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"

namespace fs = std::filesystem;

namespace simlab::cli {

CLI::Validator limitOption(const std::string& key) {
    const LimitRange& range = limitRange(key);
    return CLI::Validator(
        [range](std::string& text) {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return "must be a number, got " + text;
            const std::string bad = outOfRange(range, value);
            return bad.empty() ? std::string() : "must be between " + bad.substr(bad.find("between ") + 8);
        },
        "NUMBER");
}

Limits limitsWith(const Limits& rubric, double timeout, double memory) {
    Limits limits = rubric;
    if (timeout > 0) {
        limits.cpuSeconds = timeout;
        limits.wallSeconds = std::max(limits.wallSeconds, 6 * timeout);
    }
    if (memory > 0) limits.memoryMiB = static_cast<long>(memory);
    try {
        limits.check();
    } catch (const std::invalid_argument& e) {
        throw engine::UsageError(e.what());
    }
    return limits;
}

int cores() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

engine::SubmissionFiles readSubmission(const std::string& path, const Rubric& rubric, const Limits& limits) {
    const fs::path file(path);
    const std::string folder = file.has_parent_path() ? file.parent_path().string() : ".";
    const std::size_t cap = static_cast<std::size_t>(limits.submissionKiB) * 1024;
    engine::HandedIn source = engine::readHandedIn(folder, file.filename().string(), cap, /*followFolder=*/true);
    if (!source.found) throw engine::UsageError("source file '" + engine::printable(path) + "' does not exist");
    if (!source.ok) throw engine::UsageError(engine::printable(source.refusal));
    engine::SubmissionFiles files;
    files.name = source.name;
    files.shown = path;
    files.text = std::move(source.text);
    for (const std::string& name : rubric.extraFiles) {
        engine::HandedIn extra = engine::readHandedIn(folder, name, cap, /*followFolder=*/true);
        if (extra.found) files.extras.push_back(std::move(extra));
    }
    return files;
}

std::string selfPath() {
    std::error_code unknown;
    const fs::path self = fs::read_symlink("/proc/self/exe", unknown);
    return unknown ? "simlab" : self.string();
}

void handOver(const std::string& path, std::vector<std::string> args) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::cout.flush();
    execv(path.c_str(), argv.data());
    throw std::runtime_error("cannot run " + path + ": " + std::strerror(errno));
}

std::pair<int, int> parseShard(const std::string& text) {
    const std::size_t slash = text.find('/');
    int shard = 0, shards = 0;
    try {
        std::size_t used = 0, usedToo = 0;
        if (slash == std::string::npos) throw std::invalid_argument("no slash");
        shard = std::stoi(text.substr(0, slash), &used);
        shards = std::stoi(text.substr(slash + 1), &usedToo);
        if (used != slash || usedToo != text.size() - slash - 1) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
        throw engine::UsageError("--shard takes I/N, the share I of N (1 <= I <= N), not '" +
                                 engine::printable(text) + "'");
    }
    if (shards < 1 || shards > 10000 || shard < 1 || shard > shards) {
        throw engine::UsageError("--shard " + engine::printable(text) + ": I/N needs 1 <= I <= N <= 10000");
    }
    return {shard, shards};
}

}  // namespace simlab::cli
