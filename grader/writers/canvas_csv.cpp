// A CSV that Canvas's gradebook import takes for one assignment column: Canvas's five columns that say who the
// student is (Student, ID, SIS User ID, SIS Login ID, Section), the assignment's column, and the "Points Possible"
// row that Canvas's own export has. A blank cell leaves the grade Canvas has as it is.
#include <map>

#include "simlab/grading/report.h"
#include "simlab/common/text.h"
#include "simlab/writers/writers.h"

namespace simlab::engine {

CanvasExport canvasCsv(const std::string& column, double pointsPossible, const std::vector<RosterEntry>& roster,
                       const std::vector<StudentRecord>& records) {
    CanvasExport out;
    std::map<std::string, const StudentRecord*> byId;
    for (const StudentRecord& r : records) byId[r.id] = &r;
    out.csv = "Student,ID,SIS User ID,SIS Login ID,Section," + csvCell(column) + "\n";
    out.csv += "Points Possible,,,,," + points(pointsPossible) + "\n";
    for (const RosterEntry& e : roster) {
        out.csv += csvCell(e.student) + "," + csvCell(e.canvasId) + "," + csvCell(e.sisUserId) + "," +
                   csvCell(e.sisLoginId) + "," + csvCell(e.section) + ",";
        const auto found = e.folder.empty() ? byId.end() : byId.find(e.folder);
        // A blank cell, never a grade the student has not earned: no id, no folder, no file handed in, a grader
        // error, or points a person has still to give.
        if (e.folder.empty()) {
            out.noId.push_back(e.student);
        } else if (found == byId.end() || found->second->status == SubmissionStatus::GraderError) {
            out.notGraded.push_back(e.folder);
        } else if (found->second->status == SubmissionStatus::MissingFile) {
            out.missingFile.push_back(e.folder);
        } else if (found->second->pendingPoints() > 0) {
            out.manualPending.push_back(e.folder);
        } else {
            out.csv += points(found->second->total());
            ++out.scored;
            if (e.canvasId.empty() && e.sisUserId.empty() && e.sisLoginId.empty()) out.unmatched.push_back(e.folder);
        }
        out.csv += "\n";
    }
    for (const auto& [id, record] : byId) {
        bool listed = false;
        for (const RosterEntry& e : roster) listed = listed || e.folder == id;
        if (!listed) out.notOnRoster.push_back(id);
    }
    return out;
}

}  // namespace simlab::engine
