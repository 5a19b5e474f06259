#include "sim/util/json_file.h"

#include "core/input_error.h"
#include "scenes/loaders/file_bytes.h"

#include <fstream>
#include <sstream>

namespace rtc {

namespace {

std::size_t line_of(const std::string& text, std::size_t byte) {
    std::size_t line = 1;
    for (std::size_t i = 0; i < byte && i < text.size(); ++i) line += text[i] == '\n';
    return line;
}

// nlohmann names the number of an overflow ("number overflow parsing
// '1e400'") but not where it is: find the first number token equal to it.
std::size_t byte_of_number(const std::string& text, const std::string& token) {
    if (token.empty()) return std::string::npos;
    const auto number_char = [](char c) {
        return (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-';
    };
    for (std::size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + 1)) {
        const bool starts = at == 0 || !number_char(text[at - 1]);
        const bool ends = at + token.size() >= text.size() || !number_char(text[at + token.size()]);
        if (starts && ends) return at;
    }
    return std::string::npos;
}

}  // namespace

std::string read_text_file(const std::string& path) {
    require_regular_file(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // nlohmann reports a byte offset; turn it into a line for humans.
        std::string what = e.what();
        const auto colon = what.rfind(": ");
        throw InputError(file + ": line " + std::to_string(line_of(text, e.byte)) + ": invalid JSON" +
                         (colon == std::string::npos ? "" : what.substr(colon)));
    } catch (const nlohmann::json::exception& e) {
        // out_of_range 406: a number too large for a double, e.g. 1e400.
        std::string what = e.what();
        const auto open = what.find('\''), close = what.rfind('\'');
        const std::string token =
            open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
        const std::size_t at = byte_of_number(text, token);
        const std::string where =
            at == std::string::npos ? "" : "line " + std::to_string(line_of(text, at)) + ": ";
        const auto bracket = what.find("] ");
        throw InputError(file + ": " + where + "invalid JSON: " +
                         (bracket == std::string::npos ? what : what.substr(bracket + 2)));
    }
}

}  // namespace rtc
