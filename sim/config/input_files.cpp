#include "sim/config/input_files.h"

#include <algorithm>
#include <filesystem>

namespace rtc {

std::vector<InputFile> input_files(const std::vector<RunConfig>& points) {
    std::vector<InputFile> out;
    const auto add = [&](const std::string& path, const std::string* text) {
        const std::string normal = std::filesystem::path(path).lexically_normal().string();
        if (std::none_of(out.begin(), out.end(), [&](const InputFile& f) { return f.path == normal; }))
            out.push_back({normal, text});
    };
    const auto add_preset = [&](const PresetFiles& files) {
        if (files)
            for (const PresetFile& f : *files) add(f.path, &f.text);
    };
    for (const RunConfig& c : points) {
        const SceneDesc& s = c.scene;
        if (s.hair_mesh) add(s.hair_mesh->path.string(), nullptr);
        for (const CurveFileDesc& curve : s.curves) add(curve.path.path.string(), nullptr);
        if (s.mesh) add(s.mesh->path.path.string(), nullptr);
        if (c.workload.type == WorkloadType::Rays) add(c.workload.rays_file, nullptr);
        for (const auto& cost : c.costs)
            if (cost) add_preset(cost->files);
        if (c.memory) add_preset(c.memory->files);
    }
    return out;
}

std::vector<std::string> input_paths(const std::vector<RunConfig>& points, const std::string& config_file) {
    std::vector<std::string> out{config_file};
    for (const InputFile& f : input_files(points)) out.push_back(f.path);
    return out;
}

}  // namespace rtc
