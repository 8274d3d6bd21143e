// validate-results: checks a Gradescope results.json against the fields Gradescope documents
// (https://gradescope-autograders.readthedocs.io/en/latest/specs/): types, allowed values, no unknown keys,
// and that the top-level score is the sum of the tests' scores.
//
//   validate-results FILE|- [--score N] [--max M] [--tests K]
// Exit 0 when valid (and as expected), 1 with one line per problem otherwise.
#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

using nlohmann::json;

namespace {

std::vector<std::string> problems;

void expect(bool ok, const std::string& what) {
    if (!ok) problems.push_back(what);
}

const std::set<std::string> kVisibility = {"hidden", "after_due_date", "after_published", "visible"};
const std::set<std::string> kFormats = {"text", "html", "simple_format", "md", "ansi"};

void checkOptional(const json& j, const std::string& where, const std::string& key, json::value_t type) {
    if (!j.contains(key)) return;
    const json& v = j[key];
    const bool ok = type == json::value_t::number_float ? v.is_number() : v.type() == type;
    expect(ok, where + "." + key + " has the wrong type");
}

void checkEnum(const json& j, const std::string& where, const std::string& key, const std::set<std::string>& allowed) {
    if (!j.contains(key)) return;
    expect(j[key].is_string() && allowed.count(j[key].get<std::string>()), where + "." + key + " is not an allowed value");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: validate-results FILE|- [--score N] [--max M] [--tests K]\n";
        return 2;
    }
    double expectScore = NAN, expectMax = NAN;
    long expectTests = -1;
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string option = argv[i];
        if (option == "--score") expectScore = std::stod(argv[i + 1]);
        else if (option == "--max") expectMax = std::stod(argv[i + 1]);
        else if (option == "--tests") expectTests = std::stol(argv[i + 1]);
        else {
            std::cerr << "validate-results: unknown option " << option << "\n";
            return 2;
        }
    }
    json doc;
    try {
        if (std::string(argv[1]) == "-") {
            doc = json::parse(std::cin);
        } else {
            std::ifstream in(argv[1]);
            doc = json::parse(in);
        }
    } catch (const std::exception& e) {
        std::cout << "not JSON: " << e.what() << "\n";
        return 1;
    }

    expect(doc.is_object(), "the document is not an object");
    static const std::set<std::string> topKeys = {"score", "execution_time", "output", "output_format",
                                                  "test_output_format", "test_name_format", "visibility",
                                                  "stdout_visibility", "extra_data", "tests", "leaderboard"};
    for (auto& [key, value] : doc.items()) expect(topKeys.count(key), "unknown top-level key " + key);
    expect(doc.contains("score") && doc["score"].is_number(), "score is missing or not a number");
    checkOptional(doc, "", "execution_time", json::value_t::number_float);
    checkOptional(doc, "", "output", json::value_t::string);
    checkOptional(doc, "", "extra_data", json::value_t::object);
    checkEnum(doc, "", "output_format", kFormats);
    checkEnum(doc, "", "visibility", kVisibility);
    checkEnum(doc, "", "stdout_visibility", kVisibility);
    expect(doc.contains("tests") && doc["tests"].is_array(), "tests is missing or not an array");
    // Gradescope's leaderboard: entries of a name, a number and an order (asc or desc).
    if (doc.contains("leaderboard")) {
        expect(doc["leaderboard"].is_array(), "leaderboard is not an array");
        int entry = 0;
        for (const json& e : doc.value("leaderboard", json::array())) {
            const std::string where = "leaderboard[" + std::to_string(entry++) + "]";
            expect(e.is_object() && e.value("name", json()).is_string() && e.value("value", json()).is_number(),
                   where + " is not a name and a number");
            checkEnum(e, where, "order", {"asc", "desc"});
        }
    }

    double sum = 0, max = 0;
    static const std::set<std::string> testKeys = {"score",  "max_score",   "status",     "name",       "name_format",
                                                   "number", "output",      "output_format", "tags", "visibility",
                                                   "extra_data"};
    int index = 0;
    for (const json& t : doc.value("tests", json::array())) {
        const std::string where = "tests[" + std::to_string(index++) + "]";
        for (auto& [key, value] : t.items()) expect(testKeys.count(key), where + " has unknown key " + key);
        expect(t.contains("score") && t["score"].is_number(), where + ".score is missing or not a number");
        expect(t.contains("max_score") && t["max_score"].is_number(), where + ".max_score is missing");
        expect(t.contains("name") && t["name"].is_string() && !t["name"].get<std::string>().empty(),
               where + ".name is missing");
        checkEnum(t, where, "status", {"passed", "failed"});
        checkOptional(t, where, "output", json::value_t::string);
        checkOptional(t, where, "number", json::value_t::string);
        checkOptional(t, where, "tags", json::value_t::array);
        checkOptional(t, where, "extra_data", json::value_t::object);
        checkEnum(t, where, "visibility", kVisibility);
        checkEnum(t, where, "output_format", kFormats);
        if (t.value("score", 0.0) > t.value("max_score", 0.0) + 1e-9) problems.push_back(where + " scores above its max");
        // A hidden test is never shown, and while one is, the student sees no total: points are never hidden.
        if (t.value("visibility", "") == "hidden" && t.value("max_score", 0.0) > 0) {
            problems.push_back(where + " carries points but is hidden (the student would see no total score)");
        }
        sum += t.value("score", 0.0);
        max += t.value("max_score", 0.0);
    }
    if (doc.contains("score") && doc["score"].is_number()) {
        expect(std::abs(doc["score"].get<double>() - sum) < 1e-6, "score is not the sum of the tests' scores");
        if (!std::isnan(expectScore)) {
            expect(std::abs(doc["score"].get<double>() - expectScore) < 1e-6,
                   "score " + doc["score"].dump() + ", expected " + std::to_string(expectScore));
        }
    }
    if (!std::isnan(expectMax)) expect(std::abs(max - expectMax) < 1e-6, "the tests' max_score sum to " + std::to_string(max));
    if (expectTests >= 0) expect(static_cast<long>(doc.value("tests", json::array()).size()) == expectTests, "wrong number of tests");

    for (const std::string& p : problems) std::cout << p << "\n";
    if (problems.empty()) std::cout << "valid results.json: score " << doc["score"].dump() << ", " << index << " tests\n";
    return problems.empty() ? 0 : 1;
}
