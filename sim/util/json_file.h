// Reading text and JSON files with errors that name the file and line.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace rtc {

[[nodiscard]] std::string read_text_file(const std::string& path);
[[nodiscard]] nlohmann::json parse_json_text(const std::string& text, const std::string& file);

}  // namespace rtc
