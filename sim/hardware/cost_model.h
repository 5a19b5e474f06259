// Pricing: cycles = sum over events of count x cost. A pure function applied
// after tracing, so one traced run can be priced under many presets (cost
// sweeps, calibration) without tracing again.
#pragma once

#include "core/sinks.h"
#include "sim/hardware/execution_model.h"
#include "sim/hardware/presets/preset_file.h"
#include "sim/hardware/uncertainty/cost_uncertainty.h"

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

class JsonReader;

// Which group of program events a preset prices (core/events.h): the
// operation classes a call executed, or the programs by name (the first
// version's guesses). The other group is counted but costs 0 under it.
enum class ProgramPricing : std::uint8_t { ByName, ByOperation };

// A cost defined as a weighted sum of other events' costs (a preset entry's
// "sum_of"): the same arithmetic gets the same price in every method, e.g. an
// oriented-box test is a ray transform plus a slab test, which is exactly
// what the masquerade pays for its instance transform and unit-box test
// (docs/beyond.md, "The same price for the same arithmetic").
struct ComposedCost {
    Event target{};
    std::vector<std::pair<Event, double>> terms;  // event, weight (>= 0)
};

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
    std::vector<ComposedCost> composed;          // costs made of other costs, in order
    std::string derived_from;                    // the base preset's name (a derived preset), else empty
    PresetFiles files;                           // as read by load_cost_model (null when parsed from text)
    // Methods this machine could run by its features but does not build as
    // modelled (RDNA4 builds oriented boxes over triangles only): method ->
    // why. Still priced; tables and report.json label them hypothetical.
    std::vector<std::pair<std::string, std::string>> hypothetical;
    [[nodiscard]] std::string hypothetical_reason(std::string_view method) const;

    // Recomputes every composed cost from its terms (in the order
    // order_compositions left them): after anything changes
    // costs (a derived preset's deltas, a draw, a fit, a break-even axis).
    void settle();
    [[nodiscard]] const ComposedCost* composition(Event e) const;

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
// "source": "..."}}}; an entry may instead be {"sum_of": {"<event>": weight,
// ...}, "source"} (a ComposedCost; "value", if given, must equal the sum).
// A preset with "derived_from" is another preset plus deltas
// (sim/hardware/presets/derived_preset.h). Every event must be priced (a missing one is an error,
// so no cost silently defaults to zero), except the program group the preset
// does not use: a preset with op_* costs prices every operation class and no
// program by name, one without prices every program by name. Costs must be
// finite and >= 0. Errors name the file and JSON path.
[[nodiscard]] CostModel load_cost_model(const std::string& path);
// A "sum_of" block {"<event>": weight, ...} for the cost of `target`; every
// term must be an event `m` prices. Errors name the file and JSON path.
[[nodiscard]] ComposedCost parse_sum_of(const JsonReader& block, Event target, const CostModel& m);
// Orders sums so that each comes after the sums among its terms (settle()
// then computes them in one pass); false when they refer to each other in a cycle.
[[nodiscard]] bool order_compositions(std::vector<ComposedCost>& composed);
// After order_compositions failed, with what it left in `composed`: one
// cycle as "a -> b -> c -> a" (the sums left over also include sums that
// only depend on a cycle, which an error must not name).
[[nodiscard]] std::string composition_cycle(const std::vector<ComposedCost>& composed);
// The hardware features a preset may list; a method needs some of them
// (MethodInfo::needs, a test checks every method's needs are here).
inline constexpr const char* kHardwareFeatures[] = {"custom_primitives", "instance_transforms", "lss", "obb_nodes",
                                                    "quantized_obb_nodes"};
// A preset's "features" list, each one of kHardwareFeatures.
[[nodiscard]] std::vector<std::string> parse_features(const JsonReader& preset);
// A "hypothetical" block {"<method>": "why", ...} into m.hypothetical
// (entries for a method already there are replaced).
void parse_hypothetical(const JsonReader& block, CostModel& m);
[[nodiscard]] CostModel parse_cost_model(const std::string& text, const std::string& file);
[[nodiscard]] std::string cost_model_to_json(const CostModel& model);

}  // namespace rtc
