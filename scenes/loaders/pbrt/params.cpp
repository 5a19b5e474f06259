// Reading and checking pbrt-v4 parameter lists (see params.h).
#include "scenes/loaders/pbrt/params.h"

#include <array>
#include <utility>

namespace rtc::pbrt {

namespace {

enum class Values : std::uint8_t { Numbers, Integers, Strings, Bools, Spectrum };
struct TypeInfo {
    const char* name;
    const char* canonical;
    Values values;
    std::size_t arity;
};
constexpr std::array<TypeInfo, 17> kTypes{{
    {"integer", "integer", Values::Integers, 1}, {"float", "float", Values::Numbers, 1},
    {"point2", "point2", Values::Numbers, 2},    {"vector2", "vector2", Values::Numbers, 2},
    {"point3", "point3", Values::Numbers, 3},    {"point", "point3", Values::Numbers, 3},
    {"vector3", "vector3", Values::Numbers, 3},  {"vector", "vector3", Values::Numbers, 3},
    {"normal", "normal", Values::Numbers, 3},    {"normal3", "normal", Values::Numbers, 3},
    {"rgb", "rgb", Values::Numbers, 3},          {"color", "rgb", Values::Numbers, 3},
    {"blackbody", "blackbody", Values::Numbers, 1}, {"spectrum", "spectrum", Values::Spectrum, 1},
    {"bool", "bool", Values::Bools, 1},          {"string", "string", Values::Strings, 1},
    {"texture", "texture", Values::Strings, 1},
}};

// "type name" with blanks around and between: exactly two words.
std::pair<std::string_view, std::string_view> split_declaration(std::string_view d) {
    auto blank = [](char c) { return c == ' ' || c == '\t'; };
    std::size_t i = 0;
    while (i < d.size() && blank(d[i])) ++i;
    std::size_t j = i;
    while (j < d.size() && !blank(d[j])) ++j;
    std::size_t k = j;
    while (k < d.size() && blank(d[k])) ++k;
    std::size_t l = k;
    while (l < d.size() && !blank(d[l])) ++l;
    std::size_t m = l;
    while (m < d.size() && blank(d[m])) ++m;
    if (j == i || l == k || m != d.size()) return {};
    return {d.substr(i, j - i), d.substr(k, l - k)};
}

}  // namespace

ParamList ParamList::read(Tokenizer& t) {
    ParamList out;
    out.tokens_ = &t;
    out.line_ = t.line();
    while (t.peek() && t.peek()->is(Token::Kind::String)) {
        const Token decl = *t.next();
        const auto [type, name] = split_declaration(decl.text);
        if (type.empty())
            t.fail(decl.line, "bad parameter declaration " + decl.shown() + " (expected \"type name\")");
        const TypeInfo* info = nullptr;
        for (const TypeInfo& ti : kTypes)
            if (type == ti.name) info = &ti;
        if (!info) t.fail(decl.line, "unknown parameter type \"" + std::string(type) + "\" in " + decl.shown());
        Param p{info->canonical, std::string(name), decl.line, {}, {}};
        for (const Param& q : out.params_)
            if (q.name == p.name) t.fail(decl.line, "parameter \"" + p.name + "\" given twice");

        auto value = [&](const Token& v) {
            const bool is_bool_word = v.is(Token::Kind::Word) && (v.text == "true" || v.text == "false");
            switch (info->values) {
                case Values::Integers:
                    p.numbers.push_back(static_cast<double>(to_integer(t, v, decl.shown().c_str())));
                    return;
                case Values::Numbers: p.numbers.push_back(to_number(t, v, decl.shown().c_str())); return;
                case Values::Spectrum:
                    if (v.is(Token::Kind::String)) p.strings.emplace_back(v.text);
                    else p.numbers.push_back(to_number(t, v, decl.shown().c_str()));
                    return;
                case Values::Bools:
                    if (is_bool_word || (v.is(Token::Kind::String) && (v.text == "true" || v.text == "false"))) {
                        p.strings.emplace_back(v.text);
                        return;
                    }
                    t.fail(v.line, "expected true or false for " + decl.shown() + ", got " + v.shown());
                case Values::Strings:
                    if (!v.is(Token::Kind::String))
                        t.fail(v.line, "expected a quoted string for " + decl.shown() + ", got " + v.shown());
                    p.strings.emplace_back(v.text);
                    return;
            }
        };
        const Token first = t.require("a parameter value");
        if (first.is(Token::Kind::Open)) {
            while (true) {
                const Token v = t.require("] to close the values");
                if (v.is(Token::Kind::Close)) break;
                if (v.is(Token::Kind::Open)) t.fail(v.line, "nested [ in the values of " + decl.shown());
                value(v);
            }
        } else if (first.is(Token::Kind::Close)) {
            t.fail(first.line, "unexpected ] after " + decl.shown());
        } else {
            value(first);
        }
        const std::size_t count = p.numbers.size() + p.strings.size();
        if (count == 0) t.fail(decl.line, "no values for " + decl.shown());
        if (info->values == Values::Spectrum && !p.strings.empty() && count != 1)
            t.fail(decl.line, "a spectrum is either numbers or one name, not both, in " + decl.shown());
        if (count % info->arity != 0)
            t.fail(decl.line, std::to_string(count) + " values for " + decl.shown() + ", need a multiple of " +
                                  std::to_string(info->arity));
        out.params_.push_back(std::move(p));
    }
    return out;
}

void ParamList::fail(const Param& p, const std::string& problem) const {
    tokens_->fail(p.line, "parameter \"" + p.type + " " + p.name + "\": " + problem);
}

const Param* ParamList::find(const std::string& name, const char* type) const {
    for (const Param& p : params_) {
        if (p.name != name) continue;
        if (p.type != type) fail(p, std::string("must have type ") + type);
        return &p;
    }
    return nullptr;
}

std::string ParamList::string(const std::string& name, const std::string& fallback) const {
    const Param* p = find(name, "string");
    if (!p) return fallback;
    if (p->strings.size() != 1) fail(*p, "expected one string");
    return p->strings[0];
}

double ParamList::number(const std::string& name, const char* type, double fallback) const {
    const Param* p = find(name, type);
    if (!p) return fallback;
    if (p->numbers.size() != 1) fail(*p, "expected one value, got " + std::to_string(p->numbers.size()));
    return p->numbers[0];
}

}  // namespace rtc::pbrt
