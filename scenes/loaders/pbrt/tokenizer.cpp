// pbrt-v4 tokens (see tokenizer.h); the rules follow pbrt-v4's parser.cpp.
#include "scenes/loaders/pbrt/tokenizer.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace rtc::pbrt {

std::string Token::shown() const {
    std::string s;
    if (kind == Kind::String) s += '"';
    s.append(text.substr(0, 60));
    if (text.size() > 60) s.append("...");
    if (kind == Kind::String) s += '"';
    return s;
}

const std::optional<Token>& Tokenizer::peek() {
    if (!has_peeked_) {
        peeked_ = scan();
        has_peeked_ = true;
    }
    return peeked_;
}

std::optional<Token> Tokenizer::next() {
    if (has_peeked_) {
        has_peeked_ = false;
        if (peeked_) last_line_ = peeked_->line;
        return std::move(peeked_);
    }
    std::optional<Token> t = scan();
    if (t) last_line_ = t->line;
    return t;
}

Token Tokenizer::require(const char* what) {
    std::optional<Token> t = next();
    if (!t) fail(line_, std::string("unexpected end of file, expected ") + what);
    return *t;
}

std::optional<Token> Tokenizer::scan() {
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
    while (pos_ < src_.size()) {
        const char c = src_[pos_];
        if (c == '\n') {
            ++line_, ++pos_;
        } else if (space(c)) {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < src_.size() && src_[pos_] != '\n') ++pos_;
        } else if (c == '[' || c == ']') {
            ++pos_;
            return Token{c == '[' ? Token::Kind::Open : Token::Kind::Close,
                         std::string_view(src_).substr(pos_ - 1, 1), line_};
        } else if (c == '"') {
            const std::size_t start = ++pos_;
            bool escaped = false;
            while (true) {
                if (pos_ >= src_.size()) fail(line_, "unterminated string (end of file inside quotes)");
                const char d = src_[pos_];
                if (d == '\n') fail(line_, "unterminated string (new line inside quotes)");
                if (d == '"') break;
                if (d == '\\') {
                    escaped = true;
                    if (++pos_ >= src_.size()) fail(line_, "unterminated string (end of file after \\)");
                    if (src_[pos_] == '\n') fail(line_, "unterminated string (new line inside quotes)");
                }
                ++pos_;
            }
            const std::string_view raw = std::string_view(src_).substr(start, pos_ - start);
            ++pos_;  // the closing quote
            if (!escaped) return Token{Token::Kind::String, raw, line_};
            std::string s;
            for (std::size_t i = 0; i < raw.size(); ++i) {
                if (raw[i] != '\\') {
                    s += raw[i];
                    continue;
                }
                switch (const char e = raw[++i]) {
                    case 'b': s += '\b'; break;
                    case 'f': s += '\f'; break;
                    case 'n': s += '\n'; break;
                    case 'r': s += '\r'; break;
                    case 't': s += '\t'; break;
                    case '\\': case '\'': case '"': s += e; break;
                    default: fail(line_, std::string("unknown escape \\") + e + " in a string");
                }
            }
            unescaped_.push_back(std::move(s));
            return Token{Token::Kind::String, unescaped_.back(), line_};
        } else {
            const std::size_t start = pos_;
            while (pos_ < src_.size() && !space(src_[pos_]) && src_[pos_] != '\n' && src_[pos_] != '"' &&
                   src_[pos_] != '[' && src_[pos_] != ']' && src_[pos_] != '#')
                ++pos_;
            return Token{Token::Kind::Word, std::string_view(src_).substr(start, pos_ - start), line_};
        }
    }
    return std::nullopt;
}

namespace {
template <class T>
bool parse(std::string_view s, T& v) {
    if (s.size() > 1 && s[0] == '+') s.remove_prefix(1);  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && ptr == s.data() + s.size();
}
}  // namespace

double to_number(const Tokenizer& t, const Token& tok, const char* what) {
    double v = 0.0;
    if (!tok.is(Token::Kind::Word) || !parse(tok.text, v) || !std::isfinite(v))
        t.fail(tok.line, std::string("expected a finite number for ") + what + ", got " + tok.shown());
    return v;
}

long long to_integer(const Tokenizer& t, const Token& tok, const char* what) {
    long long v = 0;
    if (!tok.is(Token::Kind::Word) || !parse(tok.text, v) || v > std::numeric_limits<int>::max() ||
        v < std::numeric_limits<int>::min())
        t.fail(tok.line, std::string("expected an integer (32-bit) for ") + what + ", got " + tok.shown());
    return v;
}

}  // namespace rtc::pbrt
