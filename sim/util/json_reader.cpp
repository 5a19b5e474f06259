#include "sim/util/json_reader.h"

#include <cfloat>
#include <cmath>

namespace rtc {

namespace {
// Why `x` cannot be stored as a float, or "" when it can.
std::string float_problem(double x) {
    if (std::abs(x) > FLT_MAX) return " is too large for a float (it would become infinite)";
    if (x != 0.0 && std::abs(x) < FLT_MIN) return " is too small for a float (it would become 0)";
    return "";
}
}  // namespace

std::string describe(const nlohmann::json& v) {
    std::string s = v.dump();
    if (s.size() > 60) s = s.substr(0, 57) + "...";
    return s;
}

const nlohmann::json* JsonReader::find(std::string_view key) const {
    if (!j_.is_object()) return nullptr;
    const auto it = j_.find(std::string(key));
    return it == j_.end() ? nullptr : &*it;
}

void JsonReader::require_object() const {
    if (!j_.is_object()) fail("", "expected an object, got " + describe(j_));
}

void JsonReader::allow_only(std::initializer_list<std::string_view> allowed) const {
    require_object();
    for (const auto& [key, value] : j_.items()) {
        bool ok = false;
        for (std::string_view a : allowed) ok = ok || a == key;
        if (!ok) {
            std::string list;
            for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
            fail(key, "unknown key (expected one of: " + list + ")");
        }
    }
}

JsonReader JsonReader::child(std::string_view key) const {
    const nlohmann::json* v = find(key);
    if (!v) fail(key, "missing");
    if (!v->is_object()) fail(key, "expected an object, got " + describe(*v));
    return {*v, file_, key_path(key)};
}

double JsonReader::number(std::string_view key, std::optional<double> fallback, double min,
                          double max) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected a number)");
        return *fallback;
    }
    if (!v->is_number()) fail(key, "expected a number, got " + describe(*v));
    const double x = v->get<double>();
    if (!std::isfinite(x) || x < min || x > max)
        fail(key, "expected a number in [" + describe(min) + ", " + describe(max) + "], got " +
                      describe(*v));
    if (const std::string p = float_problem(x); !p.empty()) fail(key, describe(*v) + p);
    return x;
}

double JsonReader::positive(std::string_view key, std::optional<double> fallback) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected a positive number)");
        return *fallback;
    }
    if (!v->is_number() || !(v->get<double>() > 0.0) || !std::isfinite(v->get<double>()))
        fail(key, "expected a positive number, got " + describe(*v));
    if (const std::string p = float_problem(v->get<double>()); !p.empty()) fail(key, describe(*v) + p);
    return v->get<double>();
}

float JsonReader::length(std::string_view key, std::optional<double> fallback, bool allow_zero) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected a length)");
        return static_cast<float>(*fallback);
    }
    const double x = v->is_number() ? v->get<double>() : -1.0;
    const bool ok = std::isfinite(x) && ((allow_zero && x == 0.0) || (x >= kMinLength && x <= kMaxLength));
    if (!ok)
        fail(key, std::string(allow_zero ? "expected 0 or a positive number" : "expected a positive number") +
                      " in [1e-18, " + kMaxCoordinateText + "] (a length), got " + describe(*v));
    return static_cast<float>(x);
}

long long JsonReader::integer(std::string_view key, std::optional<long long> fallback,
                              long long min, long long max) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected an integer)");
        return *fallback;
    }
    const bool integral = v->is_number_integer() ||
                          (v->is_number_float() && std::floor(v->get<double>()) == v->get<double>() &&
                           std::abs(v->get<double>()) < 9e15);
    if (!integral) fail(key, "expected an integer, got " + describe(*v));
    const auto x = v->is_number_float() ? static_cast<long long>(v->get<double>())
                                        : v->get<long long>();
    if (x < min || x > max) {
        if (min == 1 && max >= (1ll << 31) - 1)
            fail(key, "expected a positive integer, got " + describe(*v));
        fail(key, "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                      "], got " + describe(*v));
    }
    return x;
}

bool JsonReader::boolean(std::string_view key, std::optional<bool> fallback) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected true or false)");
        return *fallback;
    }
    if (!v->is_boolean()) fail(key, "expected true or false, got " + describe(*v));
    return v->get<bool>();
}

std::string JsonReader::string(std::string_view key, std::optional<std::string> fallback) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected a string)");
        return *fallback;
    }
    if (!v->is_string()) fail(key, "expected a string, got " + describe(*v));
    return v->get<std::string>();
}

std::string JsonReader::choice(std::string_view key, std::optional<std::string> fallback,
                               std::initializer_list<std::string_view> choices) const {
    const std::string s = string(key, std::move(fallback));
    std::string list;
    for (std::string_view c : choices) {
        if (c == s) return s;
        list += (list.empty() ? "" : ", ") + std::string(c);
    }
    fail(key, "expected one of " + list + ", got \"" + s + "\"");
}

std::array<double, 3> JsonReader::vec3(std::string_view key,
                                       std::optional<std::array<double, 3>> fallback) const {
    const nlohmann::json* v = find(key);
    if (!v) {
        if (!fallback) fail(key, "missing (expected [x, y, z])");
        return *fallback;
    }
    if (!v->is_array() || v->size() != 3) fail(key, "expected [x, y, z], got " + describe(*v));
    std::array<double, 3> out{};
    for (int i = 0; i < 3; ++i) {
        const auto& e = (*v)[i];
        if (!e.is_number() || !std::isfinite(e.get<double>()))
            fail(key, "expected [x, y, z] of finite numbers, got " + describe(*v));
        out[i] = e.get<double>();
        if (const std::string p = float_problem(out[i]); !p.empty())
            fail(key, "component " + describe(e) + p);
    }
    return out;
}

}  // namespace rtc
