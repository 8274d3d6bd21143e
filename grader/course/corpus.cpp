#include "simlab/course/corpus.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <toml++/toml.h>

#include "simlab/common/files.h"
#include "simlab/grading/report.h"

namespace simlab::engine {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error(path + ": " + what);
}

// A student's folder or file as a case names it (percent escapes decoded): one name in its folder, nothing above it.
std::string plainName(const std::string& path, const std::string& name, const char* what) {
    if (name.empty() || name == "." || name == ".." || name.find_first_of(std::string("/\0", 2)) != std::string::npos) {
        fail(path, std::string(what) + " '" + name + "' is not one plain name (no '/', '.' or '..')");
    }
    return name;
}

}  // namespace

std::string percentDecoded(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '%' && i + 2 < text.size() + 0 && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
            out += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else if (text[i] == '%' && i + 1 < text.size() && text[i + 1] == '%') {
            out += '%';
            ++i;
        } else {
            out += text[i];
        }
    }
    return out;
}

CorpusCase loadCorpusCase(const Assignment& assignment, const simlab::Rubric& rubric, const std::string& path,
                          const std::map<std::string, std::string>& placeholders) {
    const auto withFolders = [&](std::string text) {
        for (const auto& [name, value] : placeholders) {
            for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + value.size())) {
                text.replace(at, name.size(), value);
            }
        }
        return text;
    };
    toml::table t;
    try {
        t = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        fail(path, std::string(e.description()));
    }
    CorpusCase c;
    c.name = fs::path(path).stem().string();
    c.folder = plainName(path, percentDecoded(t["folder"].value_or(c.name)), "the folder");
    c.description = t["description"].value_or(std::string());
    if (const std::optional<std::string> status = t["status"].value<std::string>()) {
        c.status = statusNamed(*status);
        if (!c.status) fail(path, "status '" + *status + "' is not one simlab names");
    }
    c.skipped = t["skipped"].value_or(false);
    const std::string base = t["base"].value_or(std::string());
    if (base != "solution" && base != "starter") fail(path, "base must be \"solution\" or \"starter\"");
    const std::string basePath = base == "solution" ? assignment.solution : assignment.starter;
    if (basePath.empty()) fail(path, "this tree has no solution for " + assignment.id);
    c.files[assignment.source].text = readFile(basePath);
    for (const std::string& extra : rubric.extraFiles) {
        const fs::path file = fs::path(basePath).parent_path() / extra;
        if (fs::exists(file)) c.files[extra].text = readFile(file.string());
    }
    const auto score = t["score"].value<double>();
    if (!score) fail(path, "score is missing");
    c.score = *score;
    if (const toml::array* edits = t["edit"].as_array()) {
        for (const toml::node& node : *edits) {
            const toml::table* edit = node.as_table();
            const auto find = edit ? (*edit)["find"].value<std::string>() : std::nullopt;
            auto replace = edit ? (*edit)["replace"].value<std::string>() : std::nullopt;
            if (!find || !replace) fail(path, "each [[edit]] needs find and replace");
            if ((*edit)["percent"].value_or(false)) replace = percentDecoded(*replace);
            replace = withFolders(*replace);
            const std::string file = (*edit)["file"].value_or(assignment.source);
            if (!c.files.count(file)) fail(path, "the " + base + " has no " + file + " to edit");
            std::string& text = c.files[file].text;
            const std::size_t at = text.find(*find);
            if (at == std::string::npos || text.find(*find, at + 1) != std::string::npos) {
                fail(path, "edit must match exactly once in the " + base + "'s " + file + ", and does not: " + *find);
            }
            text.replace(at, find->size(), *replace);
        }
    }
    if (const toml::array* files = t["file"].as_array()) {
        for (const toml::node& node : *files) {
            const toml::table* entry = node.as_table();
            const auto name = entry ? (*entry)["name"].value<std::string>() : std::nullopt;
            if (!name) fail(path, "each [[file]] needs a name");
            const std::string fileName = plainName(path, percentDecoded(*name), "a file's name");
            if ((*entry)["remove"].value_or(false)) {
                c.files.erase(fileName);
                continue;
            }
            if (const auto rename = (*entry)["rename"].value<std::string>()) {
                if (!c.files.count(fileName)) fail(path, "no " + fileName + " to rename");
                c.files[plainName(path, percentDecoded(*rename), "a file's new name")] = c.files[fileName];
                c.files.erase(fileName);
                continue;
            }
            CorpusFile f;
            f.symlink = withFolders((*entry)["symlink"].value_or(std::string()));
            f.fifo = (*entry)["fifo"].value_or(false);
            f.sparse = static_cast<unsigned long long>((*entry)["sparse_bytes"].value_or(0.0));
            f.text = (*entry)["text"].value_or(std::string());
            if ((*entry)["percent"].value_or(false)) f.text = percentDecoded(f.text);
            c.files[fileName] = f;
        }
    }
    if (const toml::array* texts = t["report_contains"].as_array()) {
        for (const toml::node& node : *texts) {
            std::vector<std::string> choice;
            if (const toml::array* either = node.as_array()) {
                for (const toml::node& one : *either) choice.push_back(one.value_or(std::string()));
            } else {
                choice.push_back(node.value_or(std::string()));
            }
            c.reportContains.push_back(choice);
        }
    }
    if (const toml::array* texts = t["report_lacks"].as_array()) {
        for (const toml::node& node : *texts) c.reportLacks.push_back(node.value_or(std::string()));
    }
    if (const toml::table* outcomes = t["outcomes"].as_table()) {
        for (auto&& [test, outcome] : *outcomes) c.outcomes[std::string(test.str())] = outcome.value_or(std::string());
    }
    if (const toml::array* tests = t["tests"].as_array()) {
        for (const toml::node& node : *tests) {
            const auto name = node.value<std::string>();
            if (!name || !rubric.find(*name))
                fail(path, "tests names '" + name.value_or("?") + "', which the rubric has not");
            c.tests.push_back(*name);
        }
    }
    for (const auto& [test, outcome] : c.outcomes) {
        if (!rubric.find(test)) fail(path, "no test named '" + test + "' in " + assignment.rubric);
        // A test the edit changes is one `check` runs: [outcomes] within `tests`.
        if (!c.tests.empty() && std::find(c.tests.begin(), c.tests.end(), test) == c.tests.end()) {
            fail(path, "'" + test + "' has an outcome of its own but is not among `tests`");
        }
    }
    if (c.tests.empty()) {
        for (const auto& [test, outcome] : c.outcomes) c.tests.push_back(test);
    }
    if (c.tests.empty() && !rubric.tests.empty()) c.tests.push_back(rubric.tests.front().name);
    c.sandbox = t["sandbox"].value_or(false);
    c.invariantEntry = t["invariant"]["entry"].value_or(std::string());
    c.invariantRuns = t["invariant"]["runs"].value_or(true);
    return c;
}

void writeCorpusCase(const CorpusCase& c, const std::string& folder, const std::string& classDir) {
    const fs::path dir(folder);
    fs::create_directories(dir);
    for (const auto& [name, file] : c.files) {
        const fs::path path = dir / name;
        std::error_code ignored;
        if (!file.symlink.empty()) {
            std::string target = file.symlink;
            const std::size_t at = target.find("{class}");
            if (at != std::string::npos) target.replace(at, 7, classDir);
            fs::remove(path, ignored);
            fs::create_symlink(target, path);
        } else if (file.fifo) {
            fs::remove(path, ignored);
            if (::mkfifo(path.c_str(), 0644) != 0)
                throw std::runtime_error("cannot make a named pipe " + path.string());
        } else if (file.sparse > 0) {
            fs::remove(path, ignored);
            const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (fd < 0 || ::ftruncate(fd, static_cast<off_t>(file.sparse)) != 0) {
                throw std::runtime_error("cannot make a sparse file " + path.string());
            }
            ::close(fd);
        } else if (fs::is_symlink(path) || !fs::exists(path) || readFile(path.string()) != file.text) {
            fs::remove(path, ignored);
            writeFileAtomically(path.string(), file.text);
        }
    }
}

std::vector<std::string> compareWithCase(const CorpusCase& c, const std::vector<TestResult>& tests,
                                         std::optional<double> score, SubmissionStatus status,
                                         const std::string& text, bool everyTest) {
    std::vector<std::string> mismatches;
    for (const TestResult& t : tests) {
        const auto listed = c.outcomes.find(t.name);
        const std::string expected = listed == c.outcomes.end() ? "passed" : listed->second;
        if (outcomeName(t.outcome) != expected) {
            mismatches.push_back("'" + t.name + "' " + outcomeName(t.outcome) + ", expected " + expected);
        }
    }
    if (score && std::abs(*score - c.score) > 0.005) {
        mismatches.push_back("score " + points(*score) + ", expected " + points(c.score));
    }
    if (c.status && status != *c.status)
        mismatches.push_back("status '" + statusName(status) + "', expected '" + statusName(*c.status) + "'");
    for (const std::vector<std::string>& choice :
         everyTest ? c.reportContains : std::vector<std::vector<std::string>>{}) {
        const bool said = std::any_of(choice.begin(), choice.end(), [&](const std::string& needle) {
            return text.find(needle) != std::string::npos;
        });
        if (said) continue;
        std::string needles;
        for (const std::string& needle : choice) needles += (needles.empty() ? "'" : " or '") + needle + "'";
        mismatches.push_back("the report does not say " + needles);
    }
    for (const std::string& needle : c.reportLacks) {
        if (text.find(needle) != std::string::npos) mismatches.push_back("the report says '" + needle + "'");
    }
    return mismatches;
}

}  // namespace simlab::engine
