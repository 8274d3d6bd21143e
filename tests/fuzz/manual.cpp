// OUT/manual.csv, the sheet a person fills in with the points of a rubric's manual items (course/manual.cpp), saved
// by a spreadsheet or an editor. A sheet that reads is written again as simlab rewrites it on every regrade, and
// reads back the same: nobody's points change by being kept, nor any comment but for its control characters, which
// simlab writes as escapes (as every CSV cell it writes); and what reads back is written and read again the same.
#include "fuzz.h"
#include "simlab/common/errors.h"
#include "simlab/common/text.h"
#include "simlab/course/manual.h"

namespace {

// The project's rubric: the lab with manual items.
const simlab::Rubric& rubric() {
    static const simlab::Rubric r = simlab::loadRubric(SIMLAB_SOURCE_DIR "/assignments/biosim/grading/rubric.toml");
    return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab::engine;
    ManualSheet sheet;
    try {
        sheet = readManualCsv(simlab::fuzz::text(data, size), "manual.csv", rubric());
    } catch (const UsageError&) {
        return 0;
    }
    std::vector<std::string> students;
    for (const auto& [student, item] : sheet.order) students.push_back(student);
    strayManualRows(sheet, students, rubric());
    const std::string written = manualCsv(sheet, {}, rubric());
    ManualSheet again;
    try {
        again = readManualCsv(written, "manual.csv", rubric());
    } catch (const UsageError& e) {
        simlab::fuzz::broken(std::string("a sheet simlab wrote does not read: ") + e.what());
    }
    simlab::fuzz::require(again.order == sheet.order, "a sheet simlab wrote reads back with other rows");
    for (const auto& [key, entry] : sheet.entries) {
        const ManualEntry& kept = again.entries.at(key);
        simlab::fuzz::require(kept.points == entry.points, "points rewritten: " + key.first + " / " + key.second);
        simlab::fuzz::require(kept.comment == printable(entry.comment),
                              "a comment rewritten: " + key.first + " / " + key.second);
        simlab::fuzz::require(kept.file == entry.file, "a file cell rewritten: " + key.first + " / " + key.second);
    }
    const ManualSheet third = readManualCsv(manualCsv(again, {}, rubric()), "manual.csv", rubric());
    simlab::fuzz::require(third.order == again.order, "a sheet read back is written with other rows");
    for (const auto& [key, entry] : again.entries) {
        const ManualEntry& kept = third.entries.at(key);
        simlab::fuzz::require(kept.points == entry.points && kept.comment == entry.comment && kept.file == entry.file,
                              "a row read back is written otherwise: " + key.first + " / " + key.second);
    }
    return 0;
}
