#include "simlab/todo.h"

namespace simlab {

namespace {
std::string baseName(const std::string& path) {
    const auto slash = path.find_last_of("/\\");
    return slash == std::string::npos ? path : path.substr(slash + 1);
}
}  // namespace

NotDoneYet::NotDoneYet(const std::string& file, int line, const std::string& task)
    : std::logic_error("not done yet (" + baseName(file) + ":" + std::to_string(line) + "): " + task),
      file_(baseName(file)),
      line_(line),
      task_(task) {}

void todo(const char* file, int line, const char* task) { throw NotDoneYet(file, line, task); }

}  // namespace simlab
