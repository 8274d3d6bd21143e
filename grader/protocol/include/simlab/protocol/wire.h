// The wire format of observations: how the student's process (the probe) and the judge exchange values as JSON.
// A struct's form is declared with SIMLAB_WIRE in its own namespace: the course's shared types in
// simlab/wire_types.h, each assignment's Scene and Sample in its observations.h. This header knows no course type
// and no Simbody: a fixed-size vector (SimTK::Vec3) is any type with a static size() and numbers at [i].
//
// Reading is strict, because the probe runs student code and what it sends is data to be checked: a missing
// field, a field of the wrong type or an array of the wrong length throws WireError naming where. A number may
// be null: JSON has no NaN or infinity, so a non-finite double is written as null and read back as NaN (the
// judge reports where a simulation produced one).
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "simlab/protocol/bounded_json.h"

namespace simlab::wire {

/// An answer that does not have the shape the protocol says.
class WireError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

inline void readValue(const nlohmann::json& j, double& value, const std::string& where) {
    if (j.is_null()) value = NAN;
    else if (j.is_number()) value = j.get<double>();
    else throw WireError(where + " is not a number");
}

inline void readValue(const nlohmann::json& j, int& value, const std::string& where) {
    if (!j.is_number_integer()) throw WireError(where + " is not an integer");
    const auto v = j.get<long long>();
    if (v < -2147483647LL || v > 2147483647LL) throw WireError(where + " is out of range");
    value = static_cast<int>(v);
}

inline void readValue(const nlohmann::json& j, bool& value, const std::string& where) {
    if (!j.is_boolean()) throw WireError(where + " is not true or false");
    value = j.get<bool>();
}

inline void readValue(const nlohmann::json& j, std::string& value, const std::string& where) {
    if (!j.is_string()) throw WireError(where + " is not a string");
    value = j.get<std::string>();
}

/// A fixed-size vector of numbers (SimTK::Vec3): a list of exactly its size.
template <class V>
auto readValue(const nlohmann::json& j, V& value, const std::string& where) -> decltype(V::size(), void(value[0] = 0.0)) {
    const auto n = static_cast<std::size_t>(V::size());
    if (!j.is_array() || j.size() != n) throw WireError(where + " is not a list of " + std::to_string(n) + " numbers");
    for (std::size_t i = 0; i < n; ++i) {
        double x = 0;
        readValue(j[i], x, where + "[" + std::to_string(i) + "]");
        value[static_cast<int>(i)] = x;
    }
}

/// A type with a from_json of its own (declared with SIMLAB_WIRE, or below).
template <class T>
auto readValue(const nlohmann::json& j, T& value, const std::string& where) -> decltype(fromJson(j, value, where)) {
    if (!j.is_object()) throw WireError(where + " is not an object");
    fromJson(j, value, where);
}

template <class T>
void readValue(const nlohmann::json& j, std::vector<T>& values, const std::string& where) {
    if (!j.is_array()) throw WireError(where + " is not a list");
    values.clear();
    values.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) {
        T value{};  // every field is read before it is kept (a SimTK::Vec3 starts uninitialized)
        readValue(j[i], value, where + "[" + std::to_string(i) + "]");
        values.push_back(value);
    }
}

/// A JSON object read as a map from its keys.
template <class T>
void readValue(const nlohmann::json& j, std::map<std::string, T>& values, const std::string& where) {
    if (!j.is_object()) throw WireError(where + " is not an object");
    values.clear();
    for (auto it = j.begin(); it != j.end(); ++it) readValue(it.value(), values[it.key()], where + "." + it.key());
}

/// Field `key` of the object `j`.
template <class T>
void readField(const nlohmann::json& j, const char* key, T& value, const std::string& where) {
    const auto found = j.find(key);
    const std::string path = where.empty() ? std::string(key) : where + "." + key;
    if (found == j.end()) throw WireError(path + " is missing");
    readValue(*found, value, path);
}

inline nlohmann::json toJson(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
inline nlohmann::json toJson(int v) { return v; }
inline nlohmann::json toJson(bool v) { return v; }
inline nlohmann::json toJson(const std::string& v) { return v; }
template <class V>
auto toJson(const V& v) -> decltype(V::size(), double(v[0]), nlohmann::json()) {
    nlohmann::json list = nlohmann::json::array();
    for (int i = 0; i < V::size(); ++i) list.push_back(toJson(double(v[i])));
    return list;
}
template <class T>
auto toJson(const T& value) -> decltype(toJsonObject(value)) { return toJsonObject(value); }
template <class T>
nlohmann::json toJson(const std::vector<T>& values) {
    nlohmann::json list = nlohmann::json::array();
    for (const T& v : values) list.push_back(toJson(v));
    return list;
}

template <class T>
nlohmann::json toJson(const std::map<std::string, T>& values) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, v] : values) object[key] = toJson(v);
    return object;
}

/// A T read from `j`, which may leave fields out: those keep their values in `defaults`.
template <class T>
T readOver(const T& defaults, const nlohmann::json& j, const std::string& where) {
    if (!j.is_object()) throw WireError(where + " is not an object");
    nlohmann::json full = toJson(defaults);
    full.merge_patch(j);
    T value = defaults;
    readValue(full, value, where);
    return value;
}

/// The first null (a non-finite number) in `j`, as a path like "samples[37].yLocation"; empty if there is none.
inline std::string firstNull(const nlohmann::json& j, const std::string& where = "") {
    if (j.is_null()) return where.empty() ? "the answer" : where;
    if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i) {
            std::string found = firstNull(j[i], where + "[" + std::to_string(i) + "]");
            if (!found.empty()) return found;
        }
    } else if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            std::string found = firstNull(it.value(), where.empty() ? it.key() : where + "." + it.key());
            if (!found.empty()) return found;
        }
    }
    return "";
}

}  // namespace simlab::wire

#define SIMLAB_WIRE_TO_FIELD(field) j[#field] = ::simlab::wire::toJson(o.field);
#define SIMLAB_WIRE_FROM_FIELD(field) ::simlab::wire::readField(j, #field, o.field, where);

/// The JSON form of a struct, field by field: SIMLAB_WIRE(Sample, time, yLocation, yVelocity). Use it in the
/// struct's own namespace.
#define SIMLAB_WIRE(Type, ...)                                                                            \
    inline nlohmann::json toJsonObject(const Type& o) {                                                   \
        nlohmann::json j = nlohmann::json::object();                                                     \
        NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(SIMLAB_WIRE_TO_FIELD, __VA_ARGS__))                      \
        return j;                                                                                         \
    }                                                                                                     \
    inline void fromJson(const nlohmann::json& j, Type& o, const std::string& where) {                    \
        NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(SIMLAB_WIRE_FROM_FIELD, __VA_ARGS__))                    \
    }
