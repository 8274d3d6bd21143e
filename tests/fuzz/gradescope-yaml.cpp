// Gradescope's submission_metadata.yml, in the download of Export Submissions (course/intake.cpp, read with
// libyaml): every submission's submitters - their names, SIDs and e-mails, each the student's or a platform's to
// write. The download beside it holds three submissions' folders, each with a file; the input is the YAML.
#include "download.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace simlab;
    const std::string& root = fuzz::scratch().fresh();
    const std::string download = root + "/download";
    for (const char* submission : {"submission_1", "submission_2", "submission_10"}) {
        std::filesystem::create_directories(download + "/" + submission);
        fuzz::write(download + "/" + submission + "/NewtonsApple.cpp", std::string("// ") + submission + "\n");
    }
    fuzz::write(download + "/submission_metadata.yml", fuzz::text(data, size));
    fuzz::takeInChecked(root, "gradescope");
    return 0;
}
