// Table: a header row plus string cells, rendered as CSV (RFC 4180), as an
// aligned Markdown pipe table and as aligned plain text for the terminal
// summary. Columns whose cells all read as numbers ("1,234", "1.23x",
// "12.0 KiB", "-3e5") are right-aligned. Also the number formatting helpers
// the reports share, all locale-independent so output is byte-stable.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

class Table {
public:
    explicit Table(std::vector<std::string> header);

    // Throws std::invalid_argument when the row's size differs from the header's.
    void add_row(std::vector<std::string> row);

    [[nodiscard]] const std::vector<std::string>& header() const { return header_; }
    [[nodiscard]] const std::vector<std::vector<std::string>>& rows() const { return rows_; }

    // RFC 4180: CRLF line ends; fields containing , " CR or LF are quoted with
    // inner quotes doubled.
    [[nodiscard]] std::string to_csv() const;
    // Pipe table, cells padded to column width, "---:" on numeric columns;
    // '|' escaped and newlines turned into "<br>".
    [[nodiscard]] std::string to_markdown() const;
    // Plain aligned columns (two spaces apart) with a dashed rule under the header.
    [[nodiscard]] std::string to_console() const;

    // True if column `c` is right-aligned (every non-empty body cell numeric).
    [[nodiscard]] bool is_numeric_column(std::size_t c) const;

private:
    std::vector<std::string> header_;
    std::vector<std::vector<std::string>> rows_;
};

// Does the cell start with a number (after optional sign, with optional
// thousands commas)? Suffixes such as "x", "%" or " MiB" are allowed.
[[nodiscard]] bool looks_numeric(std::string_view cell);

// `digits` significant digits, fixed notation for 1e-4 <= |v| < 1e15 (e.g.
// 0.00123, 1.23, 1230), scientific beyond; trailing zeros kept ("1.20"), since
// they carry the precision. "nan", "inf", "-inf" for non-finite values.
[[nodiscard]] std::string format_sig(double value, int digits = 3);
// Fixed notation with `decimals` digits after the point.
[[nodiscard]] std::string format_fixed(double value, int decimals);
// 1234567 -> "1,234,567".
[[nodiscard]] std::string format_thousands(std::int64_t value);
// 1.234 -> "1.23x" (three significant digits).
[[nodiscard]] std::string format_speedup(double ratio);
// 512 -> "512 B", 1536 -> "1.50 KiB", then MiB, GiB, TiB (binary units).
[[nodiscard]] std::string format_bytes(std::uint64_t bytes);
// 0.5 -> "500 ms", 75.2 -> "1m15s"; seconds with 3 significant digits below a minute.
[[nodiscard]] std::string format_duration(double seconds);

}  // namespace rtc
