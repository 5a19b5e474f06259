// Shared by the scene import tests: fixture paths and scratch pbrt files.
#pragma once

#include "core/aabb.h"
#include "core/input_error.h"
#include "scenes/scene.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace rtc::test {

inline const std::filesystem::path kImportFixtures = std::filesystem::path(RTCSIM_SOURCE_DIR) / "tests/fixtures";

// Writes `text` to build/test_scene_import/<name> and returns its path.
inline std::filesystem::path scratch_file(const std::string& name, const std::string& text) {
    const std::filesystem::path dir = std::filesystem::path(RTCSIM_BINARY_DIR) / "test_scene_import";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
}

inline Aabb bounds_of(const std::vector<Vec3>& points) {
    Aabb b;
    for (const Vec3& p : points) b.extend(p);
    return b;
}

// The InputError message of f(), or "(no error)".
inline std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace rtc::test
