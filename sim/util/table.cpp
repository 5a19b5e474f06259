// Table rendering and number formatting (see table.h). Numbers go through
// std::to_chars, which ignores the C locale, so reports are byte-stable.
#include "sim/util/table.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace rtc {
namespace {

// Display width: UTF-8 code points (continuation bytes do not count).
std::size_t display_width(std::string_view s) {
    return static_cast<std::size_t>(
        std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

std::string pad(std::string_view s, std::size_t width, bool right) {
    const std::size_t w = display_width(s);
    const std::string fill(width > w ? width - w : 0, ' ');
    return right ? fill + std::string(s) : std::string(s) + fill;
}

std::string markdown_cell(std::string_view s) {
    std::string out;
    for (char c : s) {
        if (c == '|') out += "\\|";
        else if (c == '\n') out += "<br>";
        else if (c != '\r') out += c;
    }
    return out;
}

std::string console_cell(std::string_view s) {
    std::string out(s);
    std::replace_if(out.begin(), out.end(), [](char c) { return c == '\n' || c == '\r' || c == '\t'; }, ' ');
    return out;
}

std::string chars(double v, std::chars_format fmt, int precision) {
    std::array<char, 400> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v, fmt, precision);
    return std::string(buf.data(), res.ptr);
}

}  // namespace

Table::Table(std::vector<std::string> header) : header_(std::move(header)) {}

void Table::add_row(std::vector<std::string> row) {
    if (row.size() != header_.size())
        throw std::invalid_argument("Table::add_row: row has " + std::to_string(row.size()) +
                                    " cells, header has " + std::to_string(header_.size()));
    rows_.push_back(std::move(row));
}

bool Table::is_numeric_column(std::size_t c) const {
    bool any = false;
    for (const auto& row : rows_) {
        if (row[c].empty()) continue;
        if (!looks_numeric(row[c])) return false;
        any = true;
    }
    return any;
}

std::string Table::to_csv() const {
    auto field = [](const std::string& s) {
        if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
        std::string out = "\"";
        for (char c : s) {
            if (c == '"') out += '"';
            out += c;
        }
        return out + "\"";
    };
    auto line = [&](const std::vector<std::string>& cells) {
        std::string out;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            if (i) out += ',';
            out += field(cells[i]);
        }
        return out + "\r\n";
    };
    std::string out = line(header_);
    for (const auto& row : rows_) out += line(row);
    return out;
}

std::string Table::to_markdown() const {
    const std::size_t n = header_.size();
    std::vector<std::vector<std::string>> cells;
    cells.reserve(rows_.size() + 1);
    for (const auto* row : {&header_}) cells.emplace_back(*row);
    for (const auto& row : rows_) cells.push_back(row);
    std::vector<std::size_t> width(n, 3);  // "---" is the narrowest rule
    for (auto& row : cells)
        for (std::size_t c = 0; c < n; ++c) {
            row[c] = markdown_cell(row[c]);
            width[c] = std::max(width[c], display_width(row[c]));
        }
    std::string out;
    auto emit = [&](const std::vector<std::string>& row) {
        out += "|";
        for (std::size_t c = 0; c < n; ++c) {
            out += ' ';
            out += pad(row[c], width[c], is_numeric_column(c));
            out += " |";
        }
        out += "\n";
    };
    emit(cells[0]);
    out += "|";
    for (std::size_t c = 0; c < n; ++c)
    {
        out += ' ';
        out += is_numeric_column(c) ? std::string(width[c] - 1, '-') + ":" : std::string(width[c], '-');
        out += " |";
    }
    out += "\n";
    for (std::size_t r = 1; r < cells.size(); ++r) emit(cells[r]);
    return out;
}

std::string Table::to_console() const {
    const std::size_t n = header_.size();
    std::vector<std::size_t> width(n, 0);
    for (std::size_t c = 0; c < n; ++c) {
        width[c] = display_width(console_cell(header_[c]));
        for (const auto& row : rows_) width[c] = std::max(width[c], display_width(console_cell(row[c])));
    }
    std::string out;
    auto emit = [&](const std::vector<std::string>& row) {
        std::string line;
        for (std::size_t c = 0; c < n; ++c)
        {
            if (c) line += "  ";
            line += pad(console_cell(row[c]), width[c], is_numeric_column(c));
        }
        while (!line.empty() && line.back() == ' ') line.pop_back();
        out += line + "\n";
    };
    emit(header_);
    std::string rule;
    for (std::size_t c = 0; c < n; ++c) {
        if (c) rule += "  ";
        rule += std::string(width[c], '-');
    }
    out += rule + "\n";
    for (const auto& row : rows_) emit(row);
    return out;
}

bool looks_numeric(std::string_view s) {
    std::size_t i = 0;
    auto digit = [&](std::size_t k) { return k < s.size() && s[k] >= '0' && s[k] <= '9'; };
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    bool mantissa = false;
    while (digit(i) || (mantissa && i < s.size() && s[i] == ',' && digit(i + 1))) {
        mantissa = true;
        ++i;
    }
    if (i < s.size() && s[i] == '.' && digit(i + 1)) {
        ++i;
        while (digit(i)) ++i;
        mantissa = true;
    }
    if (!mantissa) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        std::size_t k = i + 1;
        if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
        if (digit(k)) {
            i = k;
            while (digit(i)) ++i;
        }
    }
    const std::string_view rest = s.substr(i);
    return rest.empty() || rest == "x" || rest == "%" || rest.front() == ' ';
}

std::string format_sig(double v, int digits) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    digits = std::clamp(digits, 1, 17);
    if (v == 0.0) return "0";
    // Round to `digits` significant digits first; the exponent of the rounded
    // value decides the notation (9.996 -> 10.0, not 9.996 -> "10.00").
    const std::string sci = chars(v, std::chars_format::scientific, digits - 1);
    const int exponent = std::stoi(sci.substr(sci.find('e') + 1));
    if (exponent < -4 || exponent >= 15) return sci;
    double rounded = v;
    std::from_chars(sci.data(), sci.data() + sci.size(), rounded);
    return chars(rounded, std::chars_format::fixed, std::max(0, digits - 1 - exponent));
}

std::string format_fixed(double v, int decimals) {
    if (!std::isfinite(v)) return format_sig(v);
    return chars(v, std::chars_format::fixed, std::clamp(decimals, 0, 30));
}

std::string format_thousands(std::int64_t value) {
    const bool negative = value < 0;
    std::uint64_t mag = negative ? 0 - static_cast<std::uint64_t>(value) : static_cast<std::uint64_t>(value);
    const std::string digits = std::to_string(mag);
    std::string out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return negative ? "-" + out : out;
}

std::string format_speedup(double ratio) { return format_sig(ratio, 3) + "x"; }

std::string format_bytes(std::uint64_t bytes) {
    if (bytes < 1024) return std::to_string(bytes) + " B";
    static constexpr std::array<const char*, 5> kUnits{"KiB", "MiB", "GiB", "TiB", "PiB"};
    double v = static_cast<double>(bytes) / 1024.0;
    std::size_t u = 0;
    while (v >= 1024.0 && u + 1 < kUnits.size()) {
        v /= 1024.0;
        ++u;
    }
    return format_sig(v, 3) + " " + kUnits[u];
}

std::string format_duration(double seconds) {
    if (!std::isfinite(seconds)) return format_sig(seconds) + " s";
    if (seconds < 1.0) return format_sig(seconds * 1000.0, 3) + " ms";
    if (seconds < 60.0) return format_sig(seconds, 3) + " s";
    const auto total = static_cast<std::int64_t>(std::llround(seconds));
    auto two = [](std::int64_t x) {
        std::string s = std::to_string(x);
        if (x < 10) s.insert(s.begin(), '0');
        return s;
    };
    if (total < 3600) return std::to_string(total / 60) + "m" + two(total % 60) + "s";
    return std::to_string(total / 3600) + "h" + two(total / 60 % 60) + "m";
}

}  // namespace rtc
