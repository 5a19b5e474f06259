// What `simulate` does with a config before tracing, for the config and
// scene harnesses: --set overrides, the sweep (counted, then expanded), the
// typed parsing of every point, the calibrate block, presets, the work
// estimate (under small ceilings, so that a fuzzed count is refused rather
// than built), the scene, its conversion into primitives and the camera.
#pragma once

#include "fuzz_common.h"
#include "sim/app/run_all.h"
#include "sim/calibrate/calibrate_config.h"
#include "sim/hardware/cost_model.h"
#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"
#include "sim/hardware/memory_model.h"
#include "sim/methods/method.h"
#include "sim/config/run_config.h"
#include "sim/config/scene_config.h"
#include "sim/config/sweep.h"
#include "sim/config/work_estimate.h"
#include "sim/config/workload_config.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace rtc::fuzz {

// The input format of the harnesses that build texts larger than libFuzzer's
// input limit (fuzz_nesting, fuzz_set_depth): the first two bytes give a
// repeat count (0-262,140 in steps of 4), the rest is up to `lines` lines
// (missing ones empty).
struct RepeatedParts {
    std::size_t repeat = 0;
    std::vector<std::string> part;

    // The repeat count cut so that that many copies of `unit` characters
    // stay within 8 MB (0 for an empty unit).
    [[nodiscard]] std::size_t capped_for(std::size_t unit) const {
        constexpr std::size_t kMaxText = 8u << 20;
        return unit > 0 ? std::min(repeat, kMaxText / unit) : 0;
    }
};

// Splits an input of at least two bytes (callers return early on less).
inline RepeatedParts repeated_parts(const std::uint8_t* data, std::size_t size, std::size_t lines) {
    RepeatedParts r;
    r.repeat = 4 * (std::size_t(data[0]) | std::size_t(data[1]) << 8);
    const std::string rest(reinterpret_cast<const char*>(data) + 2, size - 2);
    std::size_t at = 0;
    while (r.part.size() < lines) {
        const std::size_t end = std::min(rest.find('\n', at), rest.size());
        r.part.push_back(at <= rest.size() ? rest.substr(at, end - at) : std::string());
        at = end + 1;
    }
    return r;
}

inline void run_pipeline(nlohmann::json config, const std::vector<std::string>& sets) {
    const std::string file = "fuzz.json";  // relative paths resolve from the working directory
    WorkLimits limits;
    limits.max_rays = 1e6;
    limits.max_memory = 16.0 * 1024 * 1024;
    limits.max_sweep_points = 16;
    if (!config.is_object()) throw InputError(file + ": /: expected a JSON object");
    for (const std::string& s : sets) apply_set(config, s, file);
    (void)sweep_point_count(config, file, limits);
    const std::vector<SweepPoint> points = expand_sweep(config, file);
    std::vector<RunConfig> parsed;
    std::vector<WorkEstimate> estimates;
    for (const SweepPoint& p : points) {
        parsed.push_back(parse_run_config(p.config, file));
        estimates.push_back(estimate_config_work(parsed.back()));
    }
    check_work(combine_work(estimates), limits, file);
    if (config.contains("calibrate")) {
        const CalibrateDesc desc = parse_calibrate(JsonReader(config, file).child("calibrate"));
        std::vector<nlohmann::json> values;
        std::vector<std::string> labels;
        for (const SweepPoint& p : points) {
            values.push_back(p.values);
            labels.push_back(p.label.empty() ? parsed.front().name : p.label);
            (void)find_target(desc, p.values, labels.back());
        }
        (void)unmatched_targets(desc, values, labels);
    }
    for (const RunConfig& c : parsed) {
        for (const std::string& p : c.cost_presets) (void)load_cost_model(p);
        (void)load_memory_model(c.memory_preset);
        const Scene scene = load_scene(c.scene);
        check_work(estimate_scene_work(c, scene), limits, file);
        const Geometry geometry = make_geometry(scene, c.kind, c.subdivision);
        if (c.workload.type != WorkloadType::Rays) (void)make_camera(c.workload, geometry_bounds(geometry));
    }
}

}  // namespace rtc::fuzz
