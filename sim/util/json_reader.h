// Strict reading of JSON configs: every error names the config file and the
// JSON path of the offending key, e.g.
//   configs/runs/x.json: /workload/spp: expected a positive integer, got -4
// Unknown keys are errors too (pbrt-v4's ReportUnused), so typos never pass
// silently.
#pragma once

#include "core/input_error.h"

#include "scenes/limits.h"

#include <nlohmann/json.hpp>

#include <array>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rtc {

// A JSON object being read, with the path that names it in messages.
class JsonReader {
public:
    JsonReader(const nlohmann::json& j, std::string file, std::string path = "")
        : j_(j), file_(std::move(file)), path_(std::move(path)) {}

    [[nodiscard]] const nlohmann::json& json() const { return j_; }
    [[nodiscard]] const std::string& file() const { return file_; }
    [[nodiscard]] const std::string& path() const { return path_; }
    [[nodiscard]] std::string key_path(std::string_view key) const {
        return path_ + "/" + std::string(key);
    }
    [[nodiscard]] bool has(std::string_view key) const {
        return j_.is_object() && j_.contains(std::string(key));
    }

    [[noreturn]] void fail(std::string_view key, const std::string& problem) const {
        throw InputError(file_ + ": " + (key.empty() ? (path_.empty() ? "/" : path_) : key_path(key)) +
                         ": " + problem);
    }
    // Throws when the object has a key outside `allowed`.
    void allow_only(std::initializer_list<std::string_view> allowed) const;
    // Throws unless the value is a JSON object.
    void require_object() const;

    [[nodiscard]] JsonReader child(std::string_view key) const;  // must be an object
    // Numbers are stored as float downstream, so number(), positive() and
    // vec3() also reject values that would overflow a float or underflow to
    // 0 (1e39, 1e-300), naming the key.
    [[nodiscard]] double number(std::string_view key, std::optional<double> fallback,
                                double min = -1e300, double max = 1e300) const;
    [[nodiscard]] double positive(std::string_view key, std::optional<double> fallback) const;
    // A scene length (radius, length, spread...): in [kMinLength, kMaxLength],
    // or 0 when `allow_zero`, so boxes, squared distances and camera framing
    // stay finite and non-zero in float; the top is the loaders' limit, the
    // range every method can build (scenes/limits.h).
    static constexpr double kMinLength = 1e-18, kMaxLength = kMaxCoordinate;
    [[nodiscard]] float length(std::string_view key, std::optional<double> fallback,
                               bool allow_zero = false) const;
    [[nodiscard]] long long integer(std::string_view key, std::optional<long long> fallback,
                                    long long min, long long max) const;
    [[nodiscard]] bool boolean(std::string_view key, std::optional<bool> fallback) const;
    [[nodiscard]] std::string string(std::string_view key,
                                     std::optional<std::string> fallback) const;
    // A string that must be one of `choices`.
    [[nodiscard]] std::string choice(std::string_view key, std::optional<std::string> fallback,
                                     std::initializer_list<std::string_view> choices) const;
    [[nodiscard]] std::array<double, 3> vec3(std::string_view key,
                                             std::optional<std::array<double, 3>> fallback) const;

private:
    [[nodiscard]] const nlohmann::json* find(std::string_view key) const;
    const nlohmann::json& j_;
    std::string file_;
    std::string path_;
};

// Short rendering of a JSON value for messages ("-4", "\"abc\"", "[1,2]").
[[nodiscard]] std::string describe(const nlohmann::json& v);

}  // namespace rtc
