// A strict check of a PLY file before assimp reads it: the header (magic,
// format, elements and property types, line by line), element counts against
// the file size (so a 100-byte file cannot declare a billion vertices), and
// for ASCII files every body line (field count, numbers, face indices in
// range). Errors name the file and line. assimp then does the reading.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

void check_ply(const std::vector<std::uint8_t>& bytes, const std::string& file);

}  // namespace rtc
