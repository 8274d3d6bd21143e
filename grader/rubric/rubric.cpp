#include "simlab/rubric/rubric.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
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
        const LimitRange* range = nullptr;
        for (const LimitRange& r : limitRanges()) {
            if (k == r.key) range = &r;
        }
        if (!range) {
            std::string known;
            for (const LimitRange& r : limitRanges()) known += (known.empty() ? "" : ", ") + std::string(r.key);
            fail(path, node, "unknown limit '" + k + "' (known: " + known + ")");
        }
        if (const std::string bad = outOfRange(*range, v); !bad.empty()) fail(path, node, bad);
        if (k == "wall_seconds") limits.wallSeconds = v;
        else if (k == "cpu_seconds") limits.cpuSeconds = v;
        else if (k == "memory_mib") limits.memoryMiB = static_cast<long>(v);
        else if (k == "output_kib") limits.outputKiB = static_cast<long>(v);
        else if (k == "file_mib") limits.fileMiB = static_cast<long>(v);
        else if (k == "processes") limits.processes = static_cast<long>(v);
        else if (k == "observation_mib") limits.observationMiB = static_cast<long>(v);
        else if (k == "submission_kib") limits.submissionKiB = static_cast<long>(v);
    }
    if (limits.wallSeconds < limits.cpuSeconds) {
        fail(path, table, "wall_seconds (the net for sleeping code) must be at least cpu_seconds");
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

ManualItem readManual(const std::string& path, const toml::table& table) {
    ManualItem item;
    bool hasName = false, hasPoints = false;
    for (auto&& [key, node] : table) {
        const std::string k(key.str());
        if (k == "name") {
            item.name = text(path, node, k);
            hasName = !item.name.empty();
        } else if (k == "points") {
            item.points = number(path, node, k);
            if (!(item.points >= 0 && item.points <= 1e6)) fail(path, node, "'points' must be between 0 and 1e6");
            hasPoints = true;
        } else if (k == "description") {
            item.description = text(path, node, k);
        } else {
            fail(path, node, "unknown key '" + k + "' in a [[manual]] item (known: name, points, description)");
        }
    }
    if (!hasName) fail(path, table, "a [[manual]] item has no name");
    if (!hasPoints) fail(path, table, "manual item '" + item.name + "' has no points");
    return item;
}

Variants readVariants(const std::string& path, const toml::node& node) {
    if (!node.is_table()) fail(path, node, "'variants' must be a table: [variants]");
    Variants v;
    for (auto&& [key, value] : *node.as_table()) {
        const std::string k(key.str());
        if (k == "per_student") {
            const std::optional<bool> on = value.value_exact<bool>();
            if (!on) fail(path, value, "'per_student' must be true or false");
            v.perStudent = *on;
        } else if (k == "seed") {
            v.seed = text(path, value, k);
        } else {
            fail(path, value, "unknown key '" + k + "' in [variants] (known: per_student, seed)");
        }
    }
    if (v.perStudent && v.seed.empty())
        fail(path, node, "[variants] per_student needs a seed (any text, the course's)");
    return v;
}

}  // namespace

const std::vector<LimitRange>& limitRanges() {
    static const std::vector<LimitRange> ranges = {
        {"cpu_seconds", 0.1, 3600, "s"},      {"wall_seconds", 1, 86400, "s"},     {"memory_mib", 64, 65536, "MiB"},
        {"output_kib", 1, 1048576, "KiB"},    {"file_mib", 1, 4096, "MiB"},        {"processes", 1, 4096, ""},
        {"observation_mib", 1, 1024, "MiB"},  {"submission_kib", 1, 65536, "KiB"}};
    return ranges;
}

const LimitRange& limitRange(const std::string& key) {
    for (const LimitRange& r : limitRanges()) {
        if (key == r.key) return r;
    }
    throw std::invalid_argument("unknown limit '" + key + "'");
}

std::string outOfRange(const LimitRange& range, double value) {
    if (value >= range.min && value <= range.max) return "";
    char text[160];
    std::snprintf(text, sizeof text, "%s must be between %g and %g%s%s, got %g", range.key, range.min, range.max,
                  *range.unit ? " " : "", range.unit, value);
    return text;
}

void Limits::check() const {
    const std::pair<const char*, double> values[] = {
        {"cpu_seconds", cpuSeconds},          {"wall_seconds", wallSeconds},    {"memory_mib", double(memoryMiB)},
        {"output_kib", double(outputKiB)},    {"file_mib", double(fileMiB)},    {"processes", double(processes)},
        {"observation_mib", double(observationMiB)}, {"submission_kib", double(submissionKiB)}};
    for (const auto& [key, value] : values) {
        if (const std::string bad = outOfRange(limitRange(key), value); !bad.empty()) throw std::invalid_argument(bad);
    }
    if (wallSeconds < cpuSeconds) throw std::invalid_argument("the wall-clock net must be at least the CPU time");
}

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
    if (name[0] == '-') return no("starts with '-', which Catch2 reads as an option");
    return true;
}

double Rubric::manualPoints() const {
    double total = 0;
    for (const ManualItem& m : manual) total += m.points;
    return total;
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
    std::ifstream in(path, std::ios::binary);
    if (!in) throw RubricError(path + ": File could not be opened for reading");
    return readRubric(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), path);
}

Rubric readRubric(const std::string& document, const std::string& path) {
    toml::table root;
    try {
        root = toml::parse(document, path);
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
        } else if (k == "manual") {
            const toml::array* items = node.as_array();
            if (!items) fail(path, node, "items graded by hand are written [[manual]]");
            for (const toml::node& m : *items) {
                if (!m.is_table()) fail(path, m, "items graded by hand are written [[manual]]");
                ManualItem item = readManual(path, *m.as_table());
                for (const ManualItem& other : rubric.manual) {
                    if (other.name == item.name) fail(path, m, "two manual items are named '" + item.name + "'");
                }
                rubric.manual.push_back(std::move(item));
            }
        } else if (k == "variants") {
            rubric.variants = readVariants(path, node);
        } else {
            fail(path, node,
                 "unknown key '" + k +
                     "' (known: assignment, title, submission, extra_files, [limits], [[test]], [[manual]], "
                     "[variants])");
        }
    }
    if (rubric.assignment.empty()) throw RubricError(path + ": 'assignment' is missing");
    if (rubric.submission.empty()) throw RubricError(path + ": 'submission' is missing");
    if (!hasTests || rubric.tests.empty()) throw RubricError(path + ": the rubric has no [[test]]");
    return rubric;
}

}  // namespace simlab
