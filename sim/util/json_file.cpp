#include "sim/util/json_file.h"

#include "core/input_error.h"

#include <fstream>
#include <sstream>

namespace rtc {

std::string read_text_file(const std::string& path) {
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
        std::size_t line = 1;
        for (std::size_t i = 0; i < e.byte && i < text.size(); ++i) line += text[i] == '\n';
        std::string what = e.what();
        const auto colon = what.rfind(": ");
        throw InputError(file + ": line " + std::to_string(line) + ": invalid JSON" +
                         (colon == std::string::npos ? "" : what.substr(colon)));
    }
}

}  // namespace rtc
