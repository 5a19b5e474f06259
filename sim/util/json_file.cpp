#include "sim/util/json_file.h"

#include "core/input_error.h"
#include "scenes/loaders/file_bytes.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
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

void check_json_depth(std::string_view text, const std::string& file) {
    int depth = 0;
    bool in_string = false;
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') ++line;
        if (in_string) {
            if (c == '\\') ++i;  // the escaped character cannot end the string
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                throw InputError(file + ": line " + std::to_string(line) + ": JSON nested deeper than " +
                                 std::to_string(kMaxJsonDepth) + " levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

int json_nesting(std::string_view text, int stop) {
    int depth = 0, deepest = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size() && deepest < stop; ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return deepest;
}

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
    check_json_depth(text, file);
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

OutputFile::OutputFile(std::string path) : path_(std::move(path)), partial_(path_ + ".partial") {
    f_ = std::fopen(partial_.c_str(), "wb");
    if (!f_) fail("cannot open for writing", errno);
}

OutputFile::~OutputFile() {
    if (!f_) return;
    std::fclose(f_);
    std::remove(partial_.c_str());
}

void OutputFile::fail(const char* what, int error) {
    if (f_) {
        std::fclose(f_);
        f_ = nullptr;
        std::remove(partial_.c_str());
    }
    throw InputError(path_ + ": " + what + (error ? std::string(" (") + std::strerror(error) + ")" : std::string()));
}

void OutputFile::write_noexcept(const void* data, std::size_t bytes) noexcept {
    if (error_ || bytes == 0 || !f_) return;
    errno = 0;
    if (std::fwrite(data, 1, bytes, f_) != bytes) error_ = errno ? errno : EIO;
}

void OutputFile::write(const void* data, std::size_t bytes) {
    write_noexcept(data, bytes);
    if (error_) fail("write failed", error_);
}

void OutputFile::commit() {
    if (!f_) fail("write failed", error_);
    if (error_) fail("write failed", error_);
    errno = 0;
    if (std::fflush(f_) != 0 || std::ferror(f_)) fail("write failed", errno ? errno : EIO);
    errno = 0;
    const int closed = std::fclose(f_);
    f_ = nullptr;
    if (closed != 0) {
        std::remove(partial_.c_str());
        fail("write failed", errno ? errno : EIO);
    }
    if (std::rename(partial_.c_str(), path_.c_str()) != 0) {
        const int e = errno;
        std::remove(partial_.c_str());
        fail("cannot rename the finished file into place", e);
    }
}

void write_file_atomically(const std::string& path, std::string_view content) {
    OutputFile f(path);
    f.write(content);
    f.commit();
}

}  // namespace rtc
