// The pbrt-v4 scene format's tokens: quoted strings (with pbrt's escapes
// \b \f \n \r \t \\ \' \"), the brackets [ and ], and bare words (directives,
// numbers, true/false); '#' starts a comment to the end of the line. Every
// token carries its line so errors can say "<file>: line N: ...". A string
// cut by a newline or by the end of the file is an error, as in pbrt-v4.
#pragma once

#include "core/input_error.h"

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>

namespace rtc::pbrt {

struct Token {
    enum class Kind : std::uint8_t { Word, String, Open, Close };
    Kind kind = Kind::Word;
    std::string_view text;  // a string's contents without quotes, escapes resolved
    std::size_t line = 0;

    [[nodiscard]] bool is(Kind k) const { return kind == k; }
    // How the token appeared, for messages: "[", "]", "Shape", "\"curve\"".
    [[nodiscard]] std::string shown() const;
};

class Tokenizer {
public:
    Tokenizer(std::string source, std::string file) : src_(std::move(source)), file_(std::move(file)) {}
    Tokenizer(const Tokenizer&) = delete;
    Tokenizer& operator=(const Tokenizer&) = delete;

    // The next token without consuming it; nullopt at the end of the file.
    [[nodiscard]] const std::optional<Token>& peek();
    // Consumes the next token; nullopt at the end of the file.
    std::optional<Token> next();
    // Consumes the next token, which must exist (`what` names what was expected).
    Token require(const char* what);

    [[nodiscard]] const std::string& file() const { return file_; }
    // The line of the last token read (or of the end of the file).
    [[nodiscard]] std::size_t line() const { return last_line_; }
    [[noreturn]] void fail(std::size_t line, const std::string& problem) const {
        throw InputError(file_ + ": line " + std::to_string(line) + ": " + problem);
    }

private:
    std::optional<Token> scan();
    std::string src_;
    std::string file_;
    std::size_t pos_ = 0;
    std::size_t line_ = 1;
    std::size_t last_line_ = 1;
    std::optional<Token> peeked_;
    bool has_peeked_ = false;
    std::deque<std::string> unescaped_;  // strings with escapes (stable addresses)
};

// Strict numbers: the whole token must be a finite number ("1.5x", "nan" and
// "1e999" are errors naming the line and the token).
[[nodiscard]] double to_number(const Tokenizer& t, const Token& tok, const char* what);
[[nodiscard]] long long to_integer(const Tokenizer& t, const Token& tok, const char* what);

}  // namespace rtc::pbrt
