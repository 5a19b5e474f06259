// The `scene` object of a simulate config -> a Scene. Three types:
//   {"type": "bundle", ...}  the paper's synthetic cylinder bundle
//   {"type": "hair", ...}    procedural hair/fur on a sphere or a mesh
//   {"type": "file", "curves": {...}, "mesh": {...}}  data files
// Every key, its default and its meaning is listed in docs/scenes.md.
// Unknown keys and bad values throw InputError naming the config file and
// the JSON path; a bad data file throws InputError naming that file.
#pragma once

#include "scenes/scene.h"
#include "sim/util/json_reader.h"

#include <filesystem>
#include <string>

namespace rtc {

[[nodiscard]] Scene load_scene(const JsonReader& scene_block);

// A data path from a config: as given if absolute, else relative to the
// config file's directory (never the working directory). Throws (naming
// `key`) if it does not exist.
[[nodiscard]] std::filesystem::path resolve_data_path(const JsonReader& block, std::string_view key);

}  // namespace rtc
