// Line-by-line reading of the text formats (curve text, SWC): '#' starts a
// comment, tokens are separated by blanks, numbers are parsed strictly (the
// whole token must be a number) so "1.5x" or "abc" is an error naming the
// line rather than a silent 0 as atof would give.
#pragma once

#include "core/input_error.h"

#include <charconv>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

class TextLines {
public:
    TextLines(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}

    // Advances to the next line; false at the end. Comments are stripped.
    bool next() {
        if (pos_ >= text_.size()) return false;
        const std::size_t end = text_.find('\n', pos_);
        const std::size_t stop = end == std::string::npos ? text_.size() : end;
        std::string_view line(text_.data() + pos_, stop - pos_);
        if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        pos_ = stop + 1;
        ++line_number_;
        tokens_.clear();
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && is_blank(line[i])) ++i;
            std::size_t j = i;
            while (j < line.size() && !is_blank(line[j])) ++j;
            if (j > i) tokens_.push_back(line.substr(i, j - i));
            i = j;
        }
        return true;
    }
    [[nodiscard]] std::size_t line_number() const { return line_number_; }
    [[nodiscard]] const std::vector<std::string_view>& tokens() const { return tokens_; }
    [[nodiscard]] bool blank() const { return tokens_.empty(); }

    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(file_ + ": line " + std::to_string(line_number_) + ": " + problem);
    }
    template <class T>
    [[nodiscard]] T number(std::size_t index, const char* what) const {
        if (index >= tokens_.size()) fail(std::string("missing ") + what);
        const std::string_view tok = tokens_[index];
        T v{};
        // from_chars rejects a leading '+', which some writers emit.
        const char* first = tok.data() + (tok.size() > 1 && tok[0] == '+' ? 1 : 0);
        const auto [ptr, ec] = std::from_chars(first, tok.data() + tok.size(), v);
        if (ec != std::errc() || ptr != tok.data() + tok.size())
            fail(std::string("expected a number for ") + what + ", got \"" + std::string(tok) + "\"");
        return v;
    }

private:
    static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
    std::string text_;
    std::string file_;
    std::size_t pos_ = 0;
    std::size_t line_number_ = 0;
    std::vector<std::string_view> tokens_;
};

}  // namespace rtc
