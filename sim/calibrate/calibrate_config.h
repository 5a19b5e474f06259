// The `calibrate` block of a simulate config: which costs to fit (with
// bounds and ties), the target speedup of each run, and where to write the
// fitted preset. Targets name a run by label, or a sweep point by the values
// of some of its sweep keys, e.g.
//   {"match": {"scene.count": 1000, "scene.tilt_deg": 45}, "speedup": 3.20}
// Format: docs/calibration.md. Parsing is strict (JsonReader): unknown keys
// are errors and every message names the file and JSON path.
#pragma once

#include "sim/calibrate/calibrate.h"
#include "sim/util/json_reader.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

struct CalibrationTarget {
    std::string label;    // matches a run label; empty when `match` is used
    nlohmann::json match;  // object {sweep key: value}; null when `label` is used
    double speedup = 1.0;  // > 0
    double weight = 1.0;   // >= 0
    std::string where;     // "<file>: <JSON path>", for messages
};

struct CalibrateDesc {
    std::vector<FitParameter> parameters;   // at least one
    std::vector<CalibrationTarget> targets; // at least one
    std::string output;       // path of the fitted preset; empty: do not write
    std::string name;         // of the fitted preset; empty: "<start>-calibrated"
    std::string description;  // empty: keep the start preset's
    std::string reference = "target speedups";  // what the targets are, for provenance
    std::string start;  // preset the fit starts from; empty: the run's first cost preset
    std::string method = "obb";  // whose speedup over the run's baseline the targets give
    int max_iterations = 200;
};

// Reads the `calibrate` object (pass the reader of that object, e.g.
// config_reader.child("calibrate"), so paths read /calibrate/...).
[[nodiscard]] CalibrateDesc parse_calibrate(const JsonReader& block);

// The `calibrate` block as planned, before any run: checked, its start
// preset loaded and its output path resolved. The fit reads this and the
// runs, never the config's JSON again.
struct CalibratePlan {
    std::string file;                // the config (messages, the fitted preset's fitted_on)
    CalibrateDesc desc;
    std::optional<CostModel> start;  // the block's `start` preset, as loaded when planned
    std::string output;              // the block's `output` resolved against the config ("": none)
};

// Plans `config`'s `calibrate` block (read from `file`). Throws InputError
// naming /calibrate/... on a bad block or a start preset that is not found
// or not valid.
[[nodiscard]] CalibratePlan plan_calibrate(const nlohmann::json& config, const std::string& file);

// The fit options a CalibrateDesc asks for.
[[nodiscard]] CalibrationOptions calibration_options(const CalibrateDesc& desc);

// The target of a run: a `label` target equal to `label`, or a `match` target
// whose every key is in `sweep_point` (an object {sweep key: value}) with an
// equal value (numbers equal to 1e-9 relative; arrays element-wise). nullptr
// when none matches; throws InputError naming both targets when two match.
[[nodiscard]] const CalibrationTarget* find_target(const CalibrateDesc& desc,
                                                   const nlohmann::json& sweep_point,
                                                   std::string_view label = {});
// The target speedup of a sweep point, by `match` targets only.
[[nodiscard]] std::optional<double> target_for(const CalibrateDesc& desc,
                                               const nlohmann::json& sweep_point_values);

// Targets that match none of the given runs (sweep point and label per run),
// as their `where`: a typo in a match value would otherwise pass silently.
[[nodiscard]] std::vector<std::string> unmatched_targets(const CalibrateDesc& desc,
                                                         const std::vector<nlohmann::json>& sweep_points,
                                                         const std::vector<std::string>& labels);

}  // namespace rtc
