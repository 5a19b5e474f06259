// A hardware preset written as another preset plus explicit, sourced deltas
// (issue "Predictions for the hardware after Turing"): later GPUs are priced
// as the calibrated Turing preset with what is known to differ, so they run
// the same execution model, inherit the fit's covariance (their speedups
// carry intervals too) and differ only where a source says they do.
//
//   {"name": "ampere", "description": "...",
//    "derived_from": "turing-calibrated.json",   // a file beside this one
//    "features": [...],                           // optional: replaces the base's
//    "execution": {...},                          // optional: overrides key by key
//    "deltas": [
//      {"events": ["triangle_test"], "scale": 0.5,
//       "source": "[D] GA102 whitepaper: twice Turing's ray/triangle rate"},
//      {"events": ["context_switch"], "value": 4, "source": "[I] ..."},
//      {"events": ["instance_transform"], "sum_of": {"op_fma": 18}, "source": "[C] ..."}]}
//
// A delta scales its events' base costs, replaces them with a value, or
// makes them a sum of other costs; every delta's source carries a tag: [D]
// documented, [M] measured, [C] read from code, [I] inferred. An event the
// deltas leave alone keeps the base's cost, its source prefixed with the
// base's name. The fit's uncertainty is inherited: a scaled event keeps its
// parameter (its draws move by the same factor), a replaced one leaves it.
#pragma once

#include "sim/hardware/cost_model.h"

namespace rtc {

class JsonReader;

// Reads a preset with "derived_from" (the base is loaded from the file named,
// relative to this preset's folder; chains of derivation are allowed up to 8
// deep). Errors name the file and JSON path.
[[nodiscard]] CostModel parse_derived_preset(const JsonReader& preset);

// Whether a source text carries one of the four tags.
[[nodiscard]] bool has_source_tag(const std::string& source);

}  // namespace rtc
