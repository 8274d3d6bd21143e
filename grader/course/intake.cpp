#include "simlab/course/intake.h"

#include <yaml.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sys/stat.h>

#include "simlab/course/batch.h"
#include "simlab/common/errors.h"
#include "simlab/common/files.h"
#include "simlab/common/text.h"
#include "simlab/course/policy.h"
#include "simlab/isolation/process.h"

namespace fs = std::filesystem;

namespace simlab::engine {

namespace {

const std::regex kCanvasFile(R"(^([^_]+)_(?:(late|LATE)_)?(\d+)_(\d+)_(.+)$)");
const std::regex kMoodleFolder(R"(^(.+)_(\d+)_assignsubmission_([a-z]+)_$)");
// Moodle's download "not in folders": each file named after its student and plugin. The name before the id and the
// file's own name after it are a person's to choose, so a name may hold the pattern again: moodleFile anchors it.
const std::regex kMoodleFile(R"(^(.+?)_(\d+)_assignsubmission_([a-z]+)_(.+)$)");
const std::regex kMoodleMark(R"(_(\d+)_assignsubmission_([a-z]+)_)");
const std::regex kResubmitted(R"(^(.*)-(\d+)(\.[^.]+)$)");  // Canvas's "NewtonsApple-2.cpp"

// A folder name for an id: letters, digits, '.', '_' and '-' kept; anything else becomes '-'.
std::string safeId(const std::string& text) {
    std::string id;
    for (unsigned char c : text) {
        const bool keep = std::isalnum(c) || c == '.' || c == '_' || c == '-';
        if (keep) id += static_cast<char>(c);
        else if (id.empty() || id.back() != '-') id += '-';
    }
    while (!id.empty() && (id.front() == '.' || id.front() == '-')) id.erase(0, 1);
    return id.empty() ? "student" : id;
}

// The modification time of `path` itself (never a link's target), as UTC text; empty when it cannot be read.
std::string fileTime(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return "";
    return utcText(st.st_mtime);
}

// The later of two UTC texts (either may be empty).
std::string later(const std::string& a, const std::string& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return *parseTime(b) > *parseTime(a) ? b : a;
}

// --- A YAML document (Gradescope's submission_metadata.yml), read with libyaml into a small tree. ---------------

struct Node {
    enum class Kind { Scalar, Map, Sequence } kind = Kind::Scalar;
    std::string value;
    std::vector<std::pair<std::string, Node>> entries;  // a map's, in order
    std::vector<Node> items;                            // a sequence's
};

// Gradescope writes Ruby symbols as keys (":name"); either spelling is found.
const Node* entryOf(const Node& map, const std::string& key) {
    if (map.kind != Node::Kind::Map) return nullptr;
    for (const auto& [k, v] : map.entries) {
        if (k == key || k == ":" + key) return &v;
    }
    return nullptr;
}

std::string scalarOf(const Node& map, const std::string& key) {
    const Node* n = entryOf(map, key);
    return n && n->kind == Node::Kind::Scalar ? n->value : "";
}

Node readYaml(const std::string& text, const std::string& where) {
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) throw UsageError("cannot read " + where + ": out of memory");
    std::unique_ptr<yaml_parser_t, void (*)(yaml_parser_t*)> guard(&parser, yaml_parser_delete);
    yaml_parser_set_input_string(&parser, reinterpret_cast<const unsigned char*>(text.data()), text.size());
    Node root;
    std::vector<Node*> open;        // the maps and sequences being filled
    std::vector<std::string> keys;  // for each open map, its pending key ("" when the next scalar is a key)
    std::vector<bool> awaitingKey;
    bool started = false;
    auto place = [&](Node node) -> Node* {
        if (open.empty()) {
            if (started) return nullptr;
            started = true;
            root = std::move(node);
            return &root;
        }
        Node* parent = open.back();
        if (parent->kind == Node::Kind::Sequence) {
            parent->items.push_back(std::move(node));
            return &parent->items.back();
        }
        if (awaitingKey.back()) {  // a key: scalars only
            keys.back() = node.value;
            awaitingKey.back() = false;
            return nullptr;
        }
        parent->entries.emplace_back(keys.back(), std::move(node));
        awaitingKey.back() = true;
        return &parent->entries.back().second;
    };
    for (;;) {
        yaml_event_t event;
        if (!yaml_parser_parse(&parser, &event)) {
            throw UsageError(where + ", line " + std::to_string(parser.problem_mark.line + 1) + ": " +
                             (parser.problem ? parser.problem : "not YAML"));
        }
        std::unique_ptr<yaml_event_t, void (*)(yaml_event_t*)> done(&event, yaml_event_delete);
        const yaml_event_type_t type = event.type;
        if (type == YAML_STREAM_END_EVENT) break;
        if (type == YAML_ALIAS_EVENT) {
            throw UsageError(where + ", line " + std::to_string(event.start_mark.line + 1) +
                             ": an alias (*name), which Gradescope's export never writes");
        }
        if (open.size() > 32) throw UsageError(where + " is nested too deep");
        if (type == YAML_SCALAR_EVENT) {
            Node n;
            n.value.assign(reinterpret_cast<const char*>(event.data.scalar.value), event.data.scalar.length);
            place(std::move(n));
        } else if (type == YAML_MAPPING_START_EVENT || type == YAML_SEQUENCE_START_EVENT) {
            Node n;
            n.kind = type == YAML_MAPPING_START_EVENT ? Node::Kind::Map : Node::Kind::Sequence;
            if (!open.empty() && open.back()->kind == Node::Kind::Map && awaitingKey.back()) {
                throw UsageError(where + ": a key that is not text");
            }
            Node* placed = place(std::move(n));
            if (!placed) throw UsageError(where + " holds more than one document");
            open.push_back(placed);
            keys.emplace_back();
            awaitingKey.push_back(true);
        } else if (type == YAML_MAPPING_END_EVENT || type == YAML_SEQUENCE_END_EVENT) {
            open.pop_back();
            keys.pop_back();
            awaitingKey.pop_back();
        }
    }
    return root;
}

// --- Copying a student's files, as untrusted data. ----------------------------------------------------------------

// Copies the file `name` of `folder` to `toDir` under `asName`; a file that cannot be taken (a link, too large)
// is said in the student's note instead.
void takeFile(const std::string& folder, const std::string& name, const std::string& toDir, const std::string& asName,
              std::size_t limit, IntakeStudent& student, bool followFolder = false) {
    const HandedIn h = readHandedIn(folder, name, limit, followFolder);
    if (!h.ok) {
        student.note += (student.note.empty() ? "" : "; ") + h.refusal;
        return;
    }
    fs::create_directories(toDir);
    if (!fs::exists(toDir + "/" + asName)) writeOutputAtomically(toDir + "/" + asName, h.text);
}

// Every regular file below `folder` (a submission as the platform keeps it), each under its own name.
// Every regular file below `folder` (a submission as the platform keeps it), each under its own name; of two files
// of one name, the one nearer the top (a folder of old attempts does not win over the file handed in).
void takeFolder(const std::string& folder, const std::string& toDir, std::size_t limit, IntakeStudent& student) {
    fs::create_directories(toDir);
    std::vector<FolderEntry> entries = walkFolder(folder);
    auto depth = [](const FolderEntry& e) { return std::count(e.name.begin(), e.name.end(), '/'); };
    std::stable_sort(entries.begin(), entries.end(),
                     [&](const FolderEntry& a, const FolderEntry& b) { return depth(a) < depth(b); });
    for (const FolderEntry& e : entries) {
        const std::string base = e.name.substr(e.name.rfind('/') + 1);
        if (base.empty() || base[0] == '.' || e.type == EntryType::Directory) continue;
        if (e.type != EntryType::Regular) {
            student.note += (student.note.empty() ? "" : "; ") + printable(e.name) + " is not a regular file: not taken";
            continue;
        }
        if (fs::exists(toDir + "/" + base)) {
            student.note += (student.note.empty() ? "" : "; ") + printable(e.name) + ": another " + printable(base) +
                            " nearer the top was taken";
            continue;
        }
        takeFile(e.folder, base, toDir, base, limit, student);
    }
}

// The student `id` of a download, made when first seen, in the download's order.
IntakeStudent& studentOf(std::map<std::string, IntakeStudent>& students, std::vector<std::string>& order,
                         const std::string& id, const std::string& name) {
    IntakeStudent& s = students[id];
    if (s.id.empty()) {
        s.id = id;
        s.name = name;
        order.push_back(id);
    }
    return s;
}

std::vector<IntakeStudent> canvas(const std::string& folder, const std::string& classDir, std::size_t limit) {
    struct Upload {
        std::string entry, original;
        long long submission = 0;
        int resubmission = 0;
        std::string prefix;  // the entry's name before the file's own: "lovelaceada_101_9001"
    };
    std::map<std::string, IntakeStudent> students;
    std::map<std::string, std::map<std::string, Upload>> uploads;  // by id, by original name: the latest
    std::vector<std::string> order;
    for (const FolderEntry& e : listFolder(folder, /*followFolder=*/true)) {
        std::smatch m;
        if (e.name[0] == '.' || !std::regex_match(e.name, m, kCanvasFile)) continue;
        IntakeStudent& s = studentOf(students, order, safeId(m[1].str() + "_" + m[3].str()), m[1]);
        s.canvasId = m[3];
        s.late = s.late || m[2].matched;
        const std::string id = s.id;
        if (m[3].length() > 15 || m[4].length() > 15) continue;  // no id Canvas makes
        Upload u{e.name, m[5], std::stoll(m[4].str()), 0, e.name.substr(0, e.name.size() - m[5].length() - 1)};
        std::smatch r;
        const std::string named = u.original;  // the match refers into it
        if (std::regex_match(named, r, kResubmitted) && r[2].length() < 6) {
            u.resubmission = std::stoi(r[2].str());
            u.original = r[1].str() + r[3].str();
        }
        Upload& kept = uploads[id][u.original];
        if (kept.entry.empty() || std::tie(u.submission, u.resubmission) > std::tie(kept.submission, kept.resubmission)) {
            kept = u;
        }
        // Canvas's zip keeps each file's submission time; the student's time is their latest file's.
        s.submitted = later(s.submitted, fileTime(folder + "/" + e.name));
        s.submittedFrom = "Canvas's file time";
    }
    std::vector<IntakeStudent> out;
    for (const std::string& id : order) {
        IntakeStudent& s = students[id];
        fs::create_directories(classDir + "/" + id);
        long long newest = -1;
        for (const auto& [original, u] : uploads[id]) {
            // Canvas's Re-Upload Submissions matches a comment to an attachment of the submission: the latest.
            if (u.submission > newest) {
                newest = u.submission;
                s.canvasFile = u.prefix;
            }
            takeFile(folder, u.entry, classDir + "/" + id, original, limit, s, /*followFolder=*/true);
            if (u.resubmission > 0) s.note += (s.note.empty() ? "" : "; ") + original + ": resubmission " + std::to_string(u.resubmission);
        }
        out.push_back(s);
    }
    return out;
}

std::vector<IntakeStudent> gradescope(const std::string& folder, const std::string& classDir, std::size_t limit) {
    const std::string metadata = folder + "/submission_metadata.yml";
    const HandedIn yml = readHandedIn(folder, "submission_metadata.yml", 16 << 20, /*followFolder=*/true);
    if (!yml.ok) throw UsageError("cannot read " + printable(metadata) + ": " + yml.refusal);
    const Node root = readYaml(yml.text, printable(metadata));
    if (root.kind != Node::Kind::Map) throw UsageError(printable(metadata) + " is not a map of submissions");
    static const std::regex folderName(R"(^[A-Za-z0-9_.-]+$)");
    std::vector<IntakeStudent> out;
    // First each submission's own id: its SID (else the e-mail's name, else the submission); a group's, its
    // members' ids joined.
    struct Submission {
        std::string name, id, names;
        std::vector<IntakeStudent> members;
        std::string created;  // created_at, as UTC text
    };
    std::vector<Submission> submissions;
    std::set<std::string> seen, ownIds;
    for (const auto& [submission, info] : root.entries) {
        if (!seen.insert(submission).second) throw UsageError(printable(metadata) + " names " + printable(submission) + " twice");
        Submission entry{submission, "", "", {}, ""};
        if (const std::optional<std::time_t> at = parseTime(scalarOf(info, "created_at"))) entry.created = utcText(*at);
        const Node* submitters = entryOf(info, "submitters");
        if (submitters && submitters->kind == Node::Kind::Sequence) {
            for (const Node& who : submitters->items) {
                IntakeStudent s;
                s.name = scalarOf(who, "name");
                s.sid = scalarOf(who, "sid");
                s.email = scalarOf(who, "email");
                entry.members.push_back(s);
            }
        }
        if (entry.members.empty()) entry.members.push_back(IntakeStudent{});
        for (IntakeStudent& s : entry.members) {
            const std::string own = !s.sid.empty() ? s.sid : !s.email.empty() ? s.email.substr(0, s.email.find('@')) : submission;
            entry.id += (entry.id.empty() ? "" : "+") + safeId(own);
            entry.names += (entry.names.empty() ? "" : ", ") + s.name;
        }
        ownIds.insert(entry.id);
        submissions.push_back(std::move(entry));
    }
    std::set<std::string> taken;
    for (Submission& entry : submissions) {
        const std::string& submission = entry.name;
        std::vector<IntakeStudent>& members = entry.members;
        const std::string& names = entry.names;
        std::string id = entry.id;
        // Ids are the students': two submissions whose students' ids are alike stay apart, and say so. The new id is
        // one no submission has taken or has as its own, whatever the SIDs (a SID may be "s42-submission_103"
        // itself, and keeps it): a clash is never two submissions in one folder.
        IntakeStudent first = members.front();
        if (taken.count(id)) {
            const std::string apart = id + "-" + safeId(submission);
            std::string unique = apart;
            for (int n = 2; taken.count(unique) || ownIds.count(unique); ++n) unique = apart + "-" + std::to_string(n);
            first.note = "the id " + id + " is another submission's too: this one is " + unique;
            id = unique;
        }
        taken.insert(id);
        first.id = id;
        const std::string dir = folder + "/" + submission;
        std::error_code error;
        if (!std::regex_match(submission, folderName) || submission == "." || submission == ".." ||
            !fs::is_directory(fs::symlink_status(dir, error))) {
            first.note += std::string(first.note.empty() ? "" : "; ") + "no folder " + printable(submission) + " in the download";
            fs::create_directories(classDir + "/" + id);
        } else {
            takeFolder(dir, classDir + "/" + id, limit, first);
        }
        for (IntakeStudent& s : members) {
            s.id = id;
            s.note = first.note;
            s.submitted = entry.created;
            if (!s.submitted.empty()) s.submittedFrom = "Gradescope's created_at";
            if (members.size() > 1) s.group = names;
            out.push_back(s);
        }
    }
    return out;
}

// The newest time of the regular files below `folder`.
std::string newestFileTime(const std::string& folder) {
    std::string newest;
    for (const FolderEntry& e : walkFolder(folder)) {
        if (e.type == EntryType::Regular) newest = later(newest, fileTime(folder + "/" + e.name));
    }
    return newest;
}

// One reading of a Moodle entry's name: the student's name and participant number, the plugin, the file's own name.
struct MoodleName {
    std::string name, id, plugin, file;
};

// Every way of reading a flat file's name "Name_123_assignsubmission_file_File.cpp": one per "_<digits>_
// assignsubmission_<plugin>_" in it (a name or a file name may hold one too).
std::vector<MoodleName> moodleReadings(const std::string& entry) {
    std::vector<MoodleName> readings;
    for (auto it = std::sregex_iterator(entry.begin(), entry.end(), kMoodleMark); it != std::sregex_iterator(); ++it) {
        const std::smatch& m = *it;
        const std::size_t at = static_cast<std::size_t>(m.position(0)),
                          after = at + static_cast<std::size_t>(m.length(0));
        if (at == 0 || after >= entry.size()) continue;
        readings.push_back({entry.substr(0, at), m[1].str(), m[2].str(), entry.substr(after)});
    }
    return readings;
}

std::vector<IntakeStudent> moodle(const std::string& folder, const std::string& classDir, std::size_t limit) {
    std::map<std::string, IntakeStudent> students;
    std::vector<std::string> order;
    // Who each participant number is, by the entries that can be read one way only: a folder (its name ends with
    // the mark, so the last one is the student's) or a file with one mark. A file that can be read several ways is
    // read the way that gives no participant another's name; if still more than one way, it is not taken.
    const std::vector<FolderEntry> entries = listFolder(folder, /*followFolder=*/true);
    std::map<std::string, std::set<std::string>> namesOf;  // participant number -> names
    for (const FolderEntry& e : entries) {
        std::smatch m;
        if (e.type == EntryType::Directory && std::regex_match(e.name, m, kMoodleFolder)) namesOf[m[2]].insert(m[1]);
        if (e.type != EntryType::Regular) continue;
        const std::vector<MoodleName> readings = moodleReadings(e.name);
        if (readings.size() == 1) namesOf[readings[0].id].insert(readings[0].name);
    }
    for (const FolderEntry& e : entries) {
        MoodleName n;
        std::smatch m;
        const bool inFolder = e.type == EntryType::Directory && std::regex_match(e.name, m, kMoodleFolder);
        if (inFolder) {
            n = {m[1], m[2], m[3], ""};
        } else if (e.type == EntryType::Regular) {
            std::vector<MoodleName> readings = moodleReadings(e.name);
            if (readings.empty()) continue;
            if (readings.size() > 1) {
                // A reading whose participant is known under another name is no reading; one known under its own
                // name is the one.
                readings.erase(std::remove_if(readings.begin(), readings.end(),
                                              [&](const MoodleName& r) {
                                                  const auto known = namesOf.find(r.id);
                                                  return known != namesOf.end() && !known->second.count(r.name);
                                              }),
                               readings.end());
                const auto own = std::find_if(readings.begin(), readings.end(),
                                              [&](const MoodleName& r) { return namesOf.count(r.id) > 0; });
                if (own != readings.end() && std::count_if(readings.begin(), readings.end(), [&](const MoodleName& r) {
                                                 return namesOf.count(r.id) > 0;
                                             }) == 1) {
                    readings = {*own};
                }
            }
            if (readings.size() != 1) {
                // Said beside the student its name gives first (the name Moodle writes first), never taken.
                const MoodleName first = readings.empty() ? moodleReadings(e.name).front() : readings.front();
                IntakeStudent& s = studentOf(students, order, safeId(first.name + "_" + first.id), first.name);
                s.platformId = first.id;
                fs::create_directories(classDir + "/" + s.id);
                s.note += (s.note.empty() ? "" : "; ") + printable(e.name) +
                          " can be read as more than one student's (its name holds another participant's number): "
                          "not taken";
                continue;
            }
            n = readings[0];
        } else {
            continue;
        }
        IntakeStudent& s = studentOf(students, order, safeId(n.name + "_" + n.id), n.name);
        s.platformId = n.id;
        const std::string id = s.id;
        fs::create_directories(classDir + "/" + id);
        // The uploaded files are graded; an online text is the same student's, and is noted.
        if (n.plugin != "file") {
            if (s.note.find("online text") == std::string::npos) {
                s.note += (s.note.empty() ? "" : "; ") + std::string("an online text too (not graded)");
            }
            continue;
        }
        if (inFolder) {
            takeFolder(folder + "/" + e.name, classDir + "/" + id, limit, s);
            s.submitted = later(s.submitted, newestFileTime(folder + "/" + e.name));
        } else {
            takeFile(folder, e.name, classDir + "/" + id, n.file, limit, s, /*followFolder=*/true);
            s.submitted = later(s.submitted, fileTime(folder + "/" + e.name));
        }
        if (!s.submitted.empty()) s.submittedFrom = "Moodle's file time";
    }
    std::vector<IntakeStudent> out;
    for (const std::string& id : order) out.push_back(students[id]);
    return out;
}

// The time of the last commit of the repository `repo` (the student's clock), as UTC text; empty when git cannot
// tell. The clone is the instructor's own, so its configuration is trusted; git runs as a tool, with no shell.
std::string commitTime(const std::string& repo) {
    try {
        const std::string dir = fs::absolute(repo).string();
        const std::string out = isolation::runTool({"/usr/bin/git", "-c", "safe.directory=*", "--no-optional-locks",
                                                    "-C", dir, "log", "-1", "--format=%cI", "HEAD"},
                                                   dir);
        const std::optional<std::time_t> t = parseTime(trimmed(out));
        return t ? utcText(*t) : "";
    } catch (const std::exception&) {
        return "";
    }
}

std::vector<IntakeStudent> classroom(const std::string& folder, const std::string& classDir,
                                     const std::vector<std::string>& handedIn, std::size_t limit) {
    std::vector<std::string> repos;
    for (const FolderEntry& e : listFolder(folder, /*followFolder=*/true)) {
        // A repository has .git; anything else there (a grades folder, say) is no student's.
        if (e.type == EntryType::Directory && e.name[0] != '.' && fs::exists(folder + "/" + e.name + "/.git")) {
            repos.push_back(e.name);
        }
    }
    // The assignment's name is what every repository's name starts with, up to its last '-' (with one repository
    // there is no telling: its whole name is the id).
    // `gh classroom clone student-repos` clones into "<assignment>-submissions": the name itself, when the folder
    // keeps it (logins that share a start, "uw-alice" and "uw-bob", keep it too).
    const std::string base = fs::path(folder).lexically_normal().filename().empty()
                                 ? fs::path(folder).lexically_normal().parent_path().filename().string()
                                 : fs::path(folder).lexically_normal().filename().string();
    const std::string suffix = "-submissions";
    std::string prefix;
    if (base.size() > suffix.size() && base.compare(base.size() - suffix.size(), suffix.size(), suffix) == 0) {
        prefix = base.substr(0, base.size() - suffix.size()) + "-";
        for (const std::string& r : repos) {
            if (r.compare(0, prefix.size(), prefix) != 0) prefix.clear();
        }
    }
    if (prefix.empty() && repos.size() >= 2) {
        prefix = repos.front();
        for (const std::string& r : repos) {
            std::size_t n = 0;
            while (n < prefix.size() && n < r.size() && prefix[n] == r[n]) ++n;
            prefix.resize(n);
        }
        // Up to the last '-' of the common start (an assignment's name may hold one). Logins that share a start
        // ("uw-alice", "uw-bob") lose it here: the folder's own name, as gh makes it, is the sure way.
        prefix = prefix.substr(0, prefix.rfind('-') + 1);  // npos + 1 is 0: no common name, no prefix
    }
    std::vector<IntakeStudent> out;
    for (const std::string& repo : repos) {
        IntakeStudent s;
        s.platformId = repo.substr(prefix.size());
        if (s.platformId.empty()) s.platformId = repo;
        s.name = s.platformId;
        s.id = safeId(s.platformId);
        fs::create_directories(classDir + "/" + s.id);
        const Submission found = findSubmission(folder + "/" + repo, handedIn.front(), /*recursive=*/true, false);
        if (found.name.empty()) {
            s.note = found.note;
        } else {
            // The file, and the files the rubric reads beside it (answers, a project description) from its folder.
            takeFile(found.folder, found.name, classDir + "/" + s.id, found.name, limit, s);
            for (std::size_t i = 1; i < handedIn.size(); ++i) {
                if (fs::exists(fs::symlink_status(found.folder + "/" + handedIn[i]))) {
                    takeFile(found.folder, handedIn[i], classDir + "/" + s.id, handedIn[i], limit, s);
                }
            }
            if (found.shown != found.name) s.note = "found at " + found.shown;
        }
        s.submitted = commitTime(folder + "/" + repo);
        if (!s.submitted.empty()) s.submittedFrom = "the last commit's time";
        out.push_back(s);
    }
    return out;
}

}  // namespace

const std::vector<std::string>& downloadLayouts() {
    static const std::vector<std::string> layouts = {"gradescope", "canvas", "moodle", "classroom"};
    return layouts;
}

std::string layoutOf(const std::string& folder) {
    if (fs::exists(folder + "/submission_metadata.yml")) return "gradescope";
    bool files = false, canvasFiles = false, folders = false, allRepositories = true, moodleFolders = false;
    for (const FolderEntry& e : listFolder(folder, /*followFolder=*/true)) {
        if (e.name[0] == '.') continue;
        if (e.type == EntryType::Directory) {
            folders = true;
            moodleFolders = moodleFolders || std::regex_match(e.name, kMoodleFolder);
            allRepositories = allRepositories && fs::exists(folder + "/" + e.name + "/.git");
        } else {
            files = true;
            canvasFiles = canvasFiles || std::regex_match(e.name, kCanvasFile);
            moodleFolders = moodleFolders || std::regex_match(e.name, kMoodleFile);
        }
    }
    if (moodleFolders) return "moodle";
    if (folders && allRepositories) return "classroom";
    if (files && !folders) return canvasFiles ? "canvas" : "loose files";
    return "";
}

std::vector<IntakeStudent> takeIn(const std::string& layout, const std::string& folder, const std::string& classDir,
                                  const std::vector<std::string>& handedIn, std::size_t limitBytes) {
    if (!fs::is_directory(folder)) throw UsageError("no folder " + printable(folder));
    // The class folder is simlab's to remake (it says so in a file of its own); never the download, nor a folder of
    // someone's that happens to have its name.
    std::error_code ignored;
    const fs::path download = fs::weakly_canonical(folder, ignored), made = fs::weakly_canonical(classDir, ignored);
    const auto within = [](const fs::path& inner, const fs::path& outer) {
        return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first == outer.end();
    };
    if (within(download, made)) {
        throw UsageError(printable(folder) + " lies in " + printable(classDir) +
                         ", which simlab remakes from the download: choose another --out");
    }
    if (within(made, download)) {
        throw UsageError(printable(classDir) + " lies in the download " + printable(folder) +
                         ": choose an --out outside it");
    }
    // The mark that the class folder is simlab's: beside it, so that it is no entry of the class.
    const std::string mark = (fs::path(classDir).parent_path() / ("." + fs::path(classDir).filename().string() + "-intake")).string();
    if (fs::exists(fs::symlink_status(classDir, ignored)) && !fs::exists(mark)) {
        throw UsageError(printable(classDir) + " exists and is not a class simlab took in: move it, or choose another --out");
    }
    fs::remove_all(classDir, ignored);
    fs::create_directories(classDir);
    writeOutputAtomically(mark, "a class simlab took in from " + printable(folder) + "\n");
    std::vector<IntakeStudent> students;
    if (layout == "canvas") students = canvas(folder, classDir, limitBytes);
    else if (layout == "gradescope") students = gradescope(folder, classDir, limitBytes);
    else if (layout == "moodle") students = moodle(folder, classDir, limitBytes);
    else if (layout == "classroom") students = classroom(folder, classDir, handedIn, limitBytes);
    else throw UsageError("unknown platform '" + printable(layout) + "' (gradescope, canvas, moodle or classroom)");
    if (students.empty()) {
        throw UsageError(printable(folder) + " is not a " + layout + " download: no submission in it is laid out as " +
                         layout + " lays them out");
    }
    return students;
}

std::string intakeRosterCsv(const std::vector<IntakeStudent>& students) {
    std::string out =
        "Student,ID,SIS User ID,SIS Login ID,Section,simlab id,Platform ID,Email,Late,Submitted,"
        "Submitted from,Group,Note,Canvas file\n";
    for (const IntakeStudent& s : students) {
        out += csvCell(s.name) + "," + csvCell(s.canvasId) + "," + csvCell(s.sid) + ",,," + csvCell(s.id) + "," +
               csvCell(s.platformId) + "," + csvCell(s.email) + "," + (s.late ? "late" : "") + "," +
               csvCell(s.submitted) + "," + csvCell(s.submittedFrom) + "," + csvCell(s.group) + "," + csvCell(s.note) +
               "," + csvCell(s.canvasFile) + "\n";
    }
    return out;
}

}  // namespace simlab::engine
