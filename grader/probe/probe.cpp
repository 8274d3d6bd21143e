// The probe's registry of observations and how one request is answered.
#include "simlab/probe/probe.h"

#include <cxxabi.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <typeinfo>

#include "simlab/todo.h"

namespace simlab::probe {

namespace {

std::map<std::string, Handler>& handlers() {
    static std::map<std::string, Handler> all;
    return all;
}

bool gSealed = false;
ThrowReporter gReporter = nullptr;

}  // namespace

std::string typeName(const std::type_info& type) {
    int status = 0;
    std::unique_ptr<char, void (*)(void*)> name(abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), std::free);
    return status == 0 && name ? name.get() : type.name();
}

void add(const std::string& kind, Handler handler) {
    if (gSealed) throw std::logic_error("the probe's observations are fixed once it serves");
    if (!handlers().emplace(kind, std::move(handler)).second) {
        throw std::logic_error("the probe's observation '" + kind + "' is the course's, and stays so");
    }
}

void seal() { gSealed = true; }

void reportThrows(ThrowReporter reporter) { gReporter = reporter; }

std::string answer(const std::string& request) {
    const nlohmann::json parsed = nlohmann::json::parse(request, nullptr, /*allow_exceptions=*/false);
    nlohmann::json reply = {{"id", parsed.is_object() ? parsed.value("id", 0) : 0}};
    try {
        if (!parsed.is_object()) throw std::logic_error("the probe received a request that is not JSON");
        const std::string kind = parsed.value("kind", "");
        const auto handler = handlers().find(kind);
        if (handler == handlers().end()) throw std::logic_error("the probe has no observation '" + kind + "'");
        reply["answer"] = handler->second(parsed.contains("arguments") ? parsed["arguments"] : nlohmann::json());
    } catch (const NotDoneYet& e) {
        reply["threw"] = {{"type", "simlab::NotDoneYet"}, {"message", e.what()}};
    } catch (const std::exception& e) {
        const std::string type = typeName(typeid(e));
        reply["threw"] = {{"type", type}, {"message", e.what()}};
        if (gReporter) gReporter(e, type);
    } catch (...) {
        reply["threw"] = {{"type", "something that is not a std::exception"}, {"message", ""}};
    }
    // Messages are the student's text: bytes that are not UTF-8 are replaced, never a reason to fail.
    return reply.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace simlab::probe
