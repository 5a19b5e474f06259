#include "sim/config/plan.h"

#include "core/input_error.h"
#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"

#include <algorithm>

namespace rtc {

double sweep_point_count(const nlohmann::json& config, const std::string& file, const WorkLimits& limits) {
    if (!config.is_object() || !config.contains("sweep")) return 1.0;
    const nlohmann::json& sweep = config["sweep"];
    const JsonReader r(sweep, file, "/sweep");
    r.require_object();
    double points = 1.0;
    std::string largest;
    std::size_t largest_size = 0;
    for (const auto& [key, values] : sweep.items()) {
        if (!values.is_array() || values.empty())
            r.fail(key, "expected a non-empty list of values, got " + describe(values));
        points *= static_cast<double>(values.size());  // doubles: no wrap, at worst inf
        if (values.size() > largest_size) {
            largest_size = values.size();
            largest = key;
        }
    }
    if (points > limits.max_sweep_points && !limits.force)
        r.fail(largest, "the sweep has " + count_text(points) + " points, more than " +
                            count_text(limits.max_sweep_points) + " (pass --force to run it anyway)");
    return points;
}

RunPlan plan_runs(nlohmann::json config, const std::string& file, const std::vector<std::string>& sets,
                  const WorkLimits& limits, const std::vector<std::string>& sweep_order) {
    if (!config.is_object()) throw InputError(file + ": /: expected a JSON object");
    RunPlan plan;
    plan.file = file;
    plan.limits = limits;
    for (const std::string& s : sets) apply_set(config, s, file);
    (void)sweep_point_count(config, file, limits);  // before expanding it
    plan.points = expand_sweep(config, file, sweep_order);
    // Every point parsed, its scene checked and its presets loaded (each file
    // once) before any work, so a bad value fails in a second; every point's
    // errors are reported, not only the first point's.
    std::vector<std::string> errors;
    const auto note = [&](const InputError& e) {
        if (std::find(errors.begin(), errors.end(), e.what()) == errors.end()) errors.emplace_back(e.what());
    };
    PresetCache presets;
    std::vector<WorkEstimate> estimates;
    for (const SweepPoint& p : plan.points) {
        try {
            plan.parsed.push_back(parse_run_config(p.config, file, &presets));
            estimates.push_back(estimate_config_work(plan.parsed.back()));
        } catch (const InputError& e) {
            note(e);
        }
    }
    if (config.contains("calibrate")) {
        try {
            plan.calibrate = plan_calibrate(config, file);  // the start preset loaded before the runs the fit needs
        } catch (const InputError& e) {
            note(e);
        }
    }
    if (!errors.empty()) {
        std::string all;
        for (const std::string& e : errors) all += (all.empty() ? "" : "\n") + e;
        throw InputError(all);
    }
    plan.work = combine_work(estimates);
    check_work(plan.work, limits, file);
    plan.config = std::move(config);
    return plan;
}

RunPlan plan_config_text(const std::string& file, const std::string& text, const std::vector<std::string>& sets,
                         const WorkLimits& limits) {
    return plan_runs(parse_json_text(text, file), file, sets, limits, sweep_key_order(text, sets));
}

}  // namespace rtc
