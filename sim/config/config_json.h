// The parsed config back as JSON, every default filled in (report.json's
// provenance/effective_config). Keys are the config keys (configs/README.md),
// so the result parses again as a config; preset and ray-file paths are
// written absolute, as they were resolved. The scene and calibrate blocks
// are written as given in `given`, the point's config (the scene's defaults
// are applied when it is loaded: docs/scenes.md).
#pragma once

#include "sim/config/run_config.h"

#include <nlohmann/json.hpp>

namespace rtc {

// What report.json writes of a sweep point besides its results: its config
// as given (overrides and sweep values applied), its sweep values, and the
// provenance the app adds (sim/app/provenance.h). The run layer carries it
// from the plan to the result without reading it.
struct PointJson {
    nlohmann::json config;
    nlohmann::json values = nlohmann::json::object();
    nlohmann::ordered_json provenance;
};

[[nodiscard]] nlohmann::ordered_json workload_to_json(const WorkloadDesc& w);
[[nodiscard]] nlohmann::ordered_json run_config_to_json(const RunConfig& c, const nlohmann::json& given);

}  // namespace rtc
