// Writing a scene's strands in formats other tools read, so that another
// renderer can trace exactly the geometry the simulator traced: the text
// curve format (load_txt reads it back bit-exactly: floats are written in
// shortest round-trip form) and Cem Yuksel's HAIR (thickness = 2 r).
#pragma once

#include "scenes/scene.h"

#include <filesystem>

namespace rtc {

// Both throw InputError naming the file if it cannot be written; write_hair
// also if a strand has more than 65,536 points (HAIR counts segments in 16 bits).
void write_txt(const Strands& strands, const std::filesystem::path& file);
void write_hair(const Strands& strands, const std::filesystem::path& file);

}  // namespace rtc
