#include "sim/app/calibrate_runs.h"

#include "core/input_error.h"
#include "sim/config/run_config.h"
#include "sim/methods/method.h"
#include "sim/run/simulation.h"
#include "sim/util/paths.h"

#include <filesystem>

#include <stdexcept>

namespace rtc {

namespace {

std::string label_of(const RunResult& r) { return r.sweep_label.empty() ? r.config.name : r.sweep_label; }

// The config as the provenance names it: relative to the working directory
// when it is below it (configs/runs/fig3_bundles.json), else as given.
std::string config_name(const std::string& file) {
    std::error_code ec;
    const auto rel = std::filesystem::relative(file, ec);
    const std::string s = rel.generic_string();
    return ec || s.empty() || s.starts_with("..") ? file : s;
}

}  // namespace

CalibrationOutcome calibrate_results(std::span<RunResult* const> runs, const CalibratePlan& plan,
                                     const WarpTraceSource& warps) {
    const std::string& file = plan.file;
    CalibrationOutcome out;
    out.desc = plan.desc;
    const CalibrateDesc& desc = out.desc;
    std::vector<CalibrationRun> fit_runs;
    std::vector<const RunResult*> fit_results;  // each fit run's RunResult
    for (RunResult* r : runs) {
        const std::string label = label_of(*r);
        const CalibrationTarget* target = find_target(desc, r->point.values, label);
        MethodRun* ref = r->baseline();
        MethodRun* obb = r->find(desc.method);
        if (!target || !ref || !obb || !ref->runnable || !obb->runnable) {
            out.skipped.push_back(label);
            continue;
        }
        CalibrationRun run{label, ref->frame.totals, obb->frame.totals, nullptr, nullptr, target->speedup,
                           target->weight, {}, {}};
        if (warps && ref->frame.warp_trace.waves() > 0 && obb->frame.warp_trace.waves() > 0) {
            run.ref_warps = warps(*r, *ref);
            run.obb_warps = warps(*r, *obb);
        }
        fit_runs.push_back(std::move(run));
        fit_results.push_back(r);
    }
    std::vector<nlohmann::json> values;
    std::vector<std::string> labels;
    for (const RunResult* r : runs) {
        values.push_back(r->point.values);
        labels.push_back(label_of(*r));
    }
    const auto unmatched = unmatched_targets(desc, values, labels);
    if (!unmatched.empty()) throw InputError(file + ": /calibrate/targets: no run matches " + unmatched.front());
    if (fit_runs.empty()) throw InputError(file + ": /calibrate/targets: no run has a target");
    try {
        // Start from the named preset (loaded when planned), else from the
        // run's primary cost preset.
        const CostModel start = plan.start ? *plan.start : runs.front()->costs.front();
        // A cost the start preset does not price (a program by name in a
        // preset that prices operation classes, or the reverse) would be
        // fitted and then dropped from the written preset: refuse it.
        for (std::size_t i = 0; i < desc.parameters.size(); ++i)
            for (std::size_t k = 0; k < desc.parameters[i].events.size(); ++k)
                if (const Event e = desc.parameters[i].events[k]; !start.prices(e))
                    throw InputError(file + ": /calibrate/parameters/" + std::to_string(i) + "/events/" +
                                     std::to_string(k) + ": the start " + start.unpriced(e));
                else if (start.composition(e))
                    throw InputError(file + ": /calibrate/parameters/" + std::to_string(i) + "/events/" +
                                     std::to_string(k) + ": " + std::string(event_name(e)) + " is a sum of other costs in \"" +
                                     start.name + "\" (sum_of): fit its terms instead");
        // The fit prices every run on the start preset's SM, for the run's
        // pipeline (the ref and fitted methods run the same programs).
        for (std::size_t i = 0; i < fit_runs.size(); ++i) {
            const RunResult& r = *fit_results[i];
            const MethodEntry* ref = find_method(r.baseline()->method);
            const MethodEntry* fitted = find_method(desc.method);
            fit_runs[i].ref_roof = method_roofline(start, r.config, ref ? ref->info.needs : std::vector<std::string>{});
            fit_runs[i].obb_roof =
                method_roofline(start, r.config, fitted ? fitted->info.needs : std::vector<std::string>{});
        }
        out.result = calibrate(fit_runs, start, desc.parameters, calibration_options(desc));
        // What it was fitted on, so runs at another resolution are told.
        const WorkloadDesc& w = runs.front()->config.workload;
        out.result.model.fitted_on = {};
        if (w.type != WorkloadType::Rays)
            out.result.model.fitted_on = {w.width, w.height, w.spp, w.bounces, config_name(file)};
    } catch (const std::invalid_argument& e) {
        throw InputError(file + ": /calibrate: " + e.what());
    }
    return out;
}

std::string calibrate_output_path(const CalibratePlan& plan, bool force) {
    if (plan.output.empty()) return "";
    std::error_code ec;
    if (std::filesystem::exists(plan.output, ec) && !force)
        throw InputError(plan.file + ": /calibrate/output: " + plan.output + " exists" +
                         (in_preset_dir(plan.output) ? " and is a shipped preset" : "") +
                         "; not overwriting it (the fitted preset is written to calibrated_preset.json in the "
                         "output directory anyway; --force overwrites " + plan.output + ")");
    return plan.output;
}

}  // namespace rtc
