// What a pbrt file held that the loaded scene drops, one line each. A run
// prints them as warnings and keeps them in report.json (scene.notes): a
// file that renders complete in pbrt would otherwise be traced without its
// spheres, or from another camera at another resolution, without a word.
#pragma once

#include "scenes/loaders/loaders.h"

#include <filesystem>
#include <string>
#include <vector>

namespace rtc::pbrt {

// "<file>: 2 sphere, 1 disk shapes skipped (...)", "<file>: Camera
// "perspective" ignored (...)", "<file>: Film resolution 64 x 64 ignored
// (...)"; empty when nothing was dropped.
[[nodiscard]] std::vector<std::string> scene_notes(const PbrtScene& scene, const std::filesystem::path& file);

}  // namespace rtc::pbrt
