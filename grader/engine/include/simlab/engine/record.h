// What grading a class keeps: each student's record (the grade and what it was made from) and the class as a whole.
// The batch (batch.h) makes them; the writers (writers.h) turn them into files.
#pragma once

#include <string>
#include <vector>

#include "simlab/engine/grade.h"

namespace simlab::engine {

/// A student's grade as kept in record.json and shown in the gradebook.
struct StudentRecord {
    std::string id;
    std::string key;     ///< what the grade was made from; a different key means regrade
    std::string status;  ///< graded, misnamed file, missing file, unsafe file, file too large, did not compile,
                         ///< forbidden code, did not link, grader error
    std::string note;
    std::string file;    ///< the file graded, relative to the student's folder
    double score = 0;
    double maxScore = 0;
    double seconds = 0;
    std::string compiler;  ///< the compiler's message: why it failed, or its warnings (first lines)
    std::string sandbox;   ///< the sandbox its code ran in, one line (empty when nothing ran)
    std::vector<TestResult> tests;
};

/// An entry of the submissions folder that is not a student: a hidden folder (its name starts with a dot), a
/// file, a link. Listed, never dropped silently.
struct Skipped {
    std::string name;
    std::string why;
};

struct ClassResult {
    std::vector<StudentRecord> records;  ///< every student in the folder, sorted by id
    std::vector<Skipped> skipped;
    int graderErrors = 0;                ///< students simlab itself could not grade (recorded; retried next run)
};

}  // namespace simlab::engine
