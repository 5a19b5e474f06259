// Pricing: cycles = sum over events of count x cost. A pure function applied
// after tracing, so one traced run can be priced under many presets (cost
// sweeps, calibration) without tracing again.
#pragma once

#include "core/sinks.h"
#include "sim/hardware/execution_model.h"
#include "sim/hardware/uncertainty/cost_uncertainty.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

// Which group of program events a preset prices (core/events.h): the
// operation classes a call executed, or the programs by name (the first
// version's guesses). The other group is counted but costs 0 under it.
enum class ProgramPricing : std::uint8_t { ByName, ByOperation };

struct CostModel {
    std::string name;
    std::string description;
    std::array<double, kEventCount> cycles{};   // cost per event
    std::array<std::string, kEventCount> source{};  // provenance of each number
    // Hardware features the preset's machine has; a method needing one it
    // lacks is priced n/a. Default: what Turing-class RT hardware has.
    std::vector<std::string> features{"custom_primitives", "instance_transforms"};
    ExecutionModel execution;  // per_ray unless the preset has an "execution" block
    ProgramPricing program_pricing = ProgramPricing::ByName;
    // The camera workload a calibrated preset was fitted on (its "fitted_on"
    // block; 0 x 0 when unknown): the warp model's answer depends on how
    // much scene a pixel tile covers, so a run at another resolution is told
    // (docs/execution-model.md, "Resolution").
    struct FittedOn {
        int width = 0, height = 0;
        std::uint32_t spp = 0, bounces = 0;
        std::string config;
        [[nodiscard]] std::uint64_t pixels() const {
            return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
        }
    } fitted_on;

    // Whether the preset prices event `e` (false: the other program group's).
    [[nodiscard]] bool prices(Event e) const;
    // Why it does not price `e` ("preset P does not price E (it prices
    // programs by ...)"), for the errors of whatever would set its cost.
    [[nodiscard]] std::string unpriced(Event e) const;
    std::optional<CostUncertainty> uncertainty;  // fitted presets: the fit's covariance (docs/calibration.md)

    [[nodiscard]] bool has_feature(std::string_view f) const;
    // The first of `needs` this preset lacks, or empty.
    [[nodiscard]] std::string missing_feature(const std::vector<std::string>& needs) const;

    [[nodiscard]] double& operator[](Event e) { return cycles[static_cast<std::size_t>(e)]; }
    [[nodiscard]] double operator[](Event e) const { return cycles[static_cast<std::size_t>(e)]; }
};

struct PricedRun {
    bool supported = true;   // false: the preset's hardware lacks a feature the method needs
    std::string missing_feature;
    ExecutionKind execution = ExecutionKind::PerRay;
    double total_cycles = 0.0;     // under the preset's execution model
    double per_ray_cycles = 0.0;   // the per-ray sum, whatever the model (for comparison)
    std::array<double, kEventCount> by_event{};  // cycles spent on each event
};

// A note when a run of `pixels` pixels is more than 4x off the resolution
// the preset was fitted at; empty otherwise (or when the preset says none).
[[nodiscard]] std::string resolution_note(const CostModel& model, std::uint64_t pixels);

[[nodiscard]] PricedRun price(const EventTotals& counts, const CostModel& model);
[[nodiscard]] double price_cycles(const RayCounts& counts, const CostModel& model);

// Reads a preset: {"name", "description", "cycles": {"<event>": {"value": x,
// "source": "..."}}}. Every event must be priced (a missing one is an error,
// so no cost silently defaults to zero), except the program group the preset
// does not use: a preset with op_* costs prices every operation class and no
// program by name, one without prices every program by name. Costs must be
// finite and >= 0. Errors name the file and JSON path.
[[nodiscard]] CostModel load_cost_model(const std::string& path);
[[nodiscard]] CostModel parse_cost_model(const std::string& text, const std::string& file);
[[nodiscard]] std::string cost_model_to_json(const CostModel& model);

}  // namespace rtc
