// What a student's feedback says, whatever its format: feedback.md and feedback.html both render this.
#pragma once

#include <string>
#include <vector>

#include "simlab/grading/record.h"

namespace simlab::engine::writers {

/// What the feedback says of points given by hand to an earlier file than the one graded (manual.h).
inline constexpr char kEarlierFile[] = "given to an earlier version of your file";

/// One test as the feedback shows it.
struct FeedbackTest {
    const TestResult* result = nullptr;
    std::string points;     ///< "8/10"
    std::string outcome;    ///< outcomeName
    bool detailed = false;  ///< has a section of its own: every test but a pass with nothing to say
    bool hidden = false;    ///< a hidden test: the student sees its points and outcome, the instructor the rest
    std::string reproduce;  ///< the command that runs it alone (a visible test that did not pass); else empty
};

/// A student's feedback, its texts as they came (each format escapes them its own way).
struct Feedback {
    std::string title;          ///< the assignment's
    std::string id;             ///< the student's
    std::string score;          ///< "85/100"
    std::string status;         ///< the record's status when it is not "graded"; else empty
    std::string note;
    std::string late;           ///< the late policy's line, with the points it took; empty without a policy
    std::string slip;           ///< the course's bank of slip days after this lab; empty where it keeps none
    std::string compilerTitle;  ///< "The compiler's message:", ...; empty when there is no message
    std::string compiler;       ///< the message, printable with its newlines
    std::vector<FeedbackTest> tests;
    std::vector<std::string> attached;  ///< files beside the feedback that the tests drew
    std::vector<ManualGrade> manual;    ///< graded by hand: the points given, or pending
    double manualPoints = 0;            ///< the points still pending
    std::string sandbox;        ///< the sandbox the code ran in, one line; empty when nothing ran
    std::string check;          ///< the self-check command for the student's file
    bool plainCommand = false;  ///< the file's name is plain enough to show the commands as code
};

Feedback feedbackOf(const Assignment& assignment, const StudentRecord& record, const std::vector<ManualItem>& manual,
                    const std::vector<std::string>& attached);

}  // namespace simlab::engine::writers
