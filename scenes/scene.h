// A scene as plain data: strands (polylines with a radius per point) and an
// optional triangle mesh. Loaders and generators produce it; conversion
// (scenes/convert.h) turns strands into primitives of one kind.
#pragma once

#include "core/ray.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

struct Strands {
    std::vector<Vec3> points;
    std::vector<float> radii;              // one per point
    std::vector<std::uint32_t> offsets{0}; // strand i is points[offsets[i], offsets[i+1])

    [[nodiscard]] std::size_t strand_count() const { return offsets.size() - 1; }
    [[nodiscard]] std::size_t segment_count() const {
        std::size_t n = 0;
        for (std::size_t i = 0; i + 1 < offsets.size(); ++i)
            n += offsets[i + 1] - offsets[i] > 0 ? offsets[i + 1] - offsets[i] - 1 : 0;
        return n;
    }
};

struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct Scene {
    std::string name;
    Strands strands;
    TriangleMesh mesh;
    // What the files held and the scene drops, one line each (e.g. a pbrt
    // file's spheres and camera): warnings, and report.json's scene.notes.
    std::vector<std::string> notes;
};

}  // namespace rtc
