// The notes of a pbrt file (see notes.h).
#include "scenes/loaders/pbrt/notes.h"

#include <cstdio>

namespace rtc::pbrt {

namespace {

std::string number_text(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", x);
    return buf;
}

}  // namespace

std::vector<std::string> scene_notes(const PbrtScene& s, const std::filesystem::path& file) {
    std::vector<std::string> out;
    const std::string name = file.string() + ": ";
    if (!s.skipped_shapes.empty()) {
        std::string list;
        std::size_t total = 0;
        for (const auto& [type, n] : s.skipped_shapes) {
            list += (list.empty() ? "" : ", ") + std::to_string(n) + " " + type;
            total += n;
        }
        out.push_back(name + list + (total == 1 ? " shape" : " shapes") +
                      " skipped (only curves and triangle meshes are traced)");
    }
    if (!s.camera.empty())
        out.push_back(name + "Camera \"" + s.camera + "\" ignored (the config's workload.camera places the camera)");
    if (s.film_resolution[0] > 0.0)
        out.push_back(name + "Film resolution " + number_text(s.film_resolution[0]) + " x " +
                      number_text(s.film_resolution[1]) +
                      " ignored (workload.width and workload.height set the image)");
    return out;
}

}  // namespace rtc::pbrt
