#include "simlab/rubric.h"

#include <set>
#include <sstream>
#include <toml++/toml.h>

namespace simlab {

namespace {

std::string where(const std::string& path, const toml::source_region& at) {
    std::ostringstream s;
    s << path;
    if (at.begin.line) s << ":" << at.begin.line << ":" << at.begin.column;
    return s.str();
}

[[noreturn]] void fail(const std::string& path, const toml::node& node, const std::string& what) {
    throw RubricError(where(path, node.source()) + ": " + what);
}

double number(const std::string& path, const toml::node& node, const std::string& key) {
    if (auto v = node.value<double>()) return *v;
    fail(path, node, "'" + key + "' must be a number");
}

std::string text(const std::string& path, const toml::node& node, const std::string& key) {
    if (auto v = node.value<std::string>()) return *v;
    fail(path, node, "'" + key + "' must be a string");
}

void readLimits(const std::string& path, const toml::table& table, Limits& limits) {
    for (auto&& [key, node] : table) {
        const std::string k(key.str());
        const double v = number(path, node, k);
        if (!(v > 0)) fail(path, node, "limit '" + k + "' must be positive");
        if (k == "wall_seconds") limits.wallSeconds = v;
        else if (k == "cpu_seconds") limits.cpuSeconds = v;
        else if (k == "memory_mib") limits.memoryMiB = static_cast<long>(v);
        else if (k == "output_kib") limits.outputKiB = static_cast<long>(v);
        else if (k == "file_mib") limits.fileMiB = static_cast<long>(v);
        else if (k == "processes") limits.processes = static_cast<long>(v);
        else fail(path, node, "unknown limit '" + k +
                                  "' (known: wall_seconds, cpu_seconds, memory_mib, output_kib, file_mib, processes)");
    }
}

RubricTest readTest(const std::string& path, const toml::table& table) {
    RubricTest test;
    bool hasName = false, hasPoints = false;
    for (auto&& [key, node] : table) {
        const std::string k(key.str());
        if (k == "name") {
            test.name = text(path, node, k);
            std::string why;
            if (!isValidTestName(test.name, &why)) fail(path, node, "test name '" + test.name + "' " + why);
            hasName = true;
        } else if (k == "points") {
            test.points = number(path, node, k);
            if (!(test.points >= 0)) fail(path, node, "'points' must not be negative");
            hasPoints = true;
        } else if (k == "visibility") {
            test.visibility = text(path, node, k);
            static const std::set<std::string> known = {"visible", "hidden", "after_due_date", "after_published"};
            if (!known.count(test.visibility)) {
                fail(path, node, "visibility '" + test.visibility +
                                     "' is not one of visible, hidden, after_due_date, after_published");
            }
        } else if (k == "description") {
            test.description = text(path, node, k);
        } else {
            test.params[k] = number(path, node, k);
        }
    }
    if (!hasName) fail(path, table, "a [[test]] has no name");
    if (!hasPoints) fail(path, table, "test '" + test.name + "' has no points");
    return test;
}

}  // namespace

bool isValidTestName(const std::string& name, std::string* why) {
    auto no = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    if (name.empty()) return no("is empty");
    if (name.find_first_of(",[]\"*~\\\n") != std::string::npos) {
        return no("holds one of , [ ] \" * ~ \\ or a newline, which Catch2 reads as test-spec syntax");
    }
    if (name.rfind("exclude:", 0) == 0) return no("starts with 'exclude:'");
    return true;
}

double Rubric::totalPoints() const {
    double total = 0;
    for (const RubricTest& t : tests) total += t.points;
    return total;
}

const RubricTest* Rubric::find(const std::string& name) const {
    for (const RubricTest& t : tests) {
        if (t.name == name) return &t;
    }
    return nullptr;
}

Rubric loadRubric(const std::string& path) {
    toml::table root;
    try {
        root = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        const std::string what(e.description());
        if (!e.source().begin.line) throw RubricError(path + ": " + what);
        throw RubricError(where(path, e.source()) + ": " + what);
    }
    Rubric rubric;
    rubric.path = path;
    bool hasTests = false;
    for (auto&& [key, node] : root) {
        const std::string k(key.str());
        if (k == "assignment") rubric.assignment = text(path, node, k);
        else if (k == "title") rubric.title = text(path, node, k);
        else if (k == "submission") rubric.submission = text(path, node, k);
        else if (k == "extra_files") {
            const toml::array* files = node.as_array();
            if (!files) fail(path, node, "'extra_files' must be a list of file names");
            for (const toml::node& f : *files) {
                const std::string name = text(path, f, "extra_files");
                if (name.empty() || name.find('/') != std::string::npos) {
                    fail(path, f, "an extra file is a plain file name, not '" + name + "'");
                }
                rubric.extraFiles.push_back(name);
            }
        }
        else if (k == "limits") {
            if (!node.is_table()) fail(path, node, "'limits' must be a table: [limits]");
            readLimits(path, *node.as_table(), rubric.limits);
        } else if (k == "test") {
            const toml::array* tests = node.as_array();
            if (!tests) fail(path, node, "tests are written [[test]]");
            for (const toml::node& t : *tests) {
                if (!t.is_table()) fail(path, t, "tests are written [[test]]");
                RubricTest test = readTest(path, *t.as_table());
                if (rubric.find(test.name)) fail(path, t, "two tests are named '" + test.name + "'");
                rubric.tests.push_back(std::move(test));
            }
            hasTests = true;
        } else {
            fail(path, node,
                 "unknown key '" + k + "' (known: assignment, title, submission, extra_files, [limits], [[test]])");
        }
    }
    if (rubric.assignment.empty()) throw RubricError(path + ": 'assignment' is missing");
    if (rubric.submission.empty()) throw RubricError(path + ": 'submission' is missing");
    if (!hasTests || rubric.tests.empty()) throw RubricError(path + ": the rubric has no [[test]]");
    return rubric;
}

}  // namespace simlab
