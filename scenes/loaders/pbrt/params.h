// A pbrt-v4 parameter list: `"type name" value` or `"type name" [ values ]`,
// repeated. Every declaration is checked when read (a known type, values of
// that type, a multiple of the type's arity, no name twice), whether or not
// the loader uses it; lookups by name then check the type the loader expects.
// Aliases as in pbrt-v4: point = point3, vector = vector3, normal3 = normal,
// color = rgb.
#pragma once

#include "scenes/loaders/pbrt/tokenizer.h"

#include <string>
#include <vector>

namespace rtc::pbrt {

struct Param {
    std::string type;  // canonical name (aliases resolved)
    std::string name;
    std::size_t line = 0;
    std::vector<double> numbers;             // numeric types (integers are exact in double)
    std::vector<std::string> strings;        // string, texture, bool ("true"/"false"), spectrum names
};

class ParamList {
public:
    // Reads declarations while the next token is a quoted string.
    static ParamList read(Tokenizer& t);

    // The values of `name`, which must have type `type` if present; nullptr
    // when absent.
    [[nodiscard]] const Param* find(const std::string& name, const char* type) const;
    [[nodiscard]] std::string string(const std::string& name, const std::string& fallback) const;
    [[nodiscard]] double number(const std::string& name, const char* type, double fallback) const;

    [[nodiscard]] std::size_t line() const { return line_; }
    [[nodiscard]] const std::vector<Param>& all() const { return params_; }

    // Throws "<file>: line N: parameter "type name": problem".
    [[noreturn]] void fail(const Param& p, const std::string& problem) const;
    // Throws at the line where the list started (the directive's line).
    [[noreturn]] void fail(const std::string& problem) const { tokens_->fail(line_, problem); }

private:
    const Tokenizer* tokens_ = nullptr;
    std::size_t line_ = 0;
    std::vector<Param> params_;
};

}  // namespace rtc::pbrt
