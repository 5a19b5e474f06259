// The files a preset was loaded from, as they were read: report.json's
// provenance records these texts (not the files as they are when the report
// is written, which an edit during the run would change), and a shard
// records their hashes so that a merge refuses presets edited in between.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace rtc {

struct PresetFile {
    std::string path;  // absolute
    std::string text;  // the bytes parsed
};

// A preset's own file first, then, for a derived preset, its base's, and
// so on down the chain. Shared: models are copied per draw and fit step.
using PresetFiles = std::shared_ptr<const std::vector<PresetFile>>;

// `files` with `path` (made absolute) and `text` put in front.
[[nodiscard]] PresetFiles prepend_preset_file(const std::string& path, std::string text, const PresetFiles& files);

}  // namespace rtc
