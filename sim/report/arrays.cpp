// Per-pixel (or per-ray) arrays of a run as NumPy .npy files, with a sidecar
// arrays.json naming the events in order and each array's totals (layout in
// docs/outputs.md).
#include "sim/plot/plot_svg.h"
#include "sim/report/npy.h"
#include "sim/report/report.h"
#include "sim/util/paths.h"

#include <filesystem>

namespace rtc {

namespace {

static_assert(sizeof(RayCounts) == kEventCount * sizeof(std::uint32_t), "RayCounts must be E packed uint32");

}  // namespace

std::vector<std::string> write_arrays(const RunResult& run, const std::string& dir) {
    std::vector<std::string> written;
    nlohmann::ordered_json side;
    side["events"] = nlohmann::ordered_json::array();
    for (const std::string_view e : kEventNames) side["events"].push_back(std::string(e));
    nlohmann::ordered_json methods = nlohmann::ordered_json::object();
    for (const MethodRun& m : run.methods) {
        if (!m.runnable) {
            methods[m.method] = {{"n/a", m.reason}};
            continue;
        }
        const FrameResult& f = m.frame;
        const bool image = f.width > 0 && !f.pixel_counts.empty();
        const auto& counts = image ? f.pixel_counts : f.ray_counts;
        if (counts.empty()) continue;
        std::vector<std::size_t> shape;
        if (image) shape = {static_cast<std::size_t>(f.height), static_cast<std::size_t>(f.width)};
        else shape = {counts.size()};
        std::vector<std::size_t> count_shape = shape;
        count_shape.push_back(kEventCount);
        nlohmann::ordered_json entry;
        const std::string counts_file = "counts_" + file_name_part(m.method) + ".npy";
        write_npy((std::filesystem::path(dir) / counts_file).string(), NpyType::U32, count_shape, counts.data());
        written.push_back(counts_file);
        entry["counts"] = {{"file", counts_file}, {"shape", count_shape}, {"dtype", "uint32"},
                           {"per", image ? "pixel (summed over samples and bounces)" : "ray (file order)"}};
        entry["totals"] = nlohmann::ordered_json::object();
        for (std::size_t i = 0; i < kEventCount; ++i) entry["totals"][std::string(kEventNames[i])] = f.totals.n[i];
        nlohmann::ordered_json cycles = nlohmann::ordered_json::object();
        for (std::size_t p = 0; p < run.costs.size(); ++p) {
            const CostModel& cost = run.costs[p];
            const bool warp = cost.execution.warp();
            if (!m.priced[p].supported) {
                cycles[cost.name] = {{"n/a", "the preset's hardware has no " + m.priced[p].missing_feature}};
                continue;
            }
            std::vector<double> values(counts.size());
            if (warp) {
                const PresetWarp* w = image ? f.warp_of(cost.name) : nullptr;
                const std::vector<float>* shares = w ? &w->pixel_cycles : nullptr;
                if (!shares || shares->size() != values.size()) {
                    cycles[cost.name] = {{"n/a", "the warp model prices waves, not single rays of a ray list"}};
                    continue;
                }
                for (std::size_t i = 0; i < values.size(); ++i) values[i] = (*shares)[i];
            } else {
                for (std::size_t i = 0; i < values.size(); ++i) values[i] = price_cycles(counts[i], cost);
            }
            const std::string file = "cycles_" + file_name_part(m.method) + "_" + file_name_part(cost.name) + ".npy";
            write_npy((std::filesystem::path(dir) / file).string(), shape, values);
            written.push_back(file);
            cycles[cost.name] = {{"file", file}, {"shape", shape}, {"dtype", "float64"},
                                 {"execution", warp ? "warp" : "per_ray"},
                                 {"total", m.priced[p].total_cycles}};
        }
        entry["cycles"] = cycles;
        methods[m.method] = entry;
    }
    if (written.empty()) return written;
    side["methods"] = methods;
    write_text_file((std::filesystem::path(dir) / "arrays.json").string(), side.dump(2) + "\n");
    written.push_back("arrays.json");
    return written;
}

}  // namespace rtc
