// One simulated run: load the scene, convert it into primitives, build each
// method, trace the workload through it, price the counts under every cost
// preset and the structures under the memory preset.
#pragma once

#include "scenes/stats.h"
#include "sim/area_stats.h"
#include "sim/cost_model.h"
#include "sim/frame.h"
#include "sim/memory_model.h"
#include "sim/run_config.h"
#include "sim/work_estimate.h"

#include <string>
#include <vector>

namespace rtc {

struct MethodRun {
    Method method = Method::Ref;
    bool runnable = true;
    std::string reason;                // why not runnable
    std::uint64_t instances = 0;
    double build_seconds = 0.0;
    StructureCounts structures;
    std::size_t simulator_bytes = 0;   // the simulator's own structures (not the model)
    FrameResult frame;
    std::vector<PricedRun> priced;     // one per cost preset, in config order
    MemoryBreakdown memory;
};

struct RunResult {
    RunConfig config;
    nlohmann::json effective_config;
    nlohmann::json sweep_values = nlohmann::json::object();
    std::string sweep_label;
    SceneStats scene;
    AreaStats areas;
    std::uint64_t primitives = 0;
    std::vector<CostModel> costs;
    MemoryModel memory;
    Camera camera;                     // resolved camera (camera workloads)
    std::vector<MethodRun> methods;
    double load_seconds = 0.0, convert_seconds = 0.0, total_seconds = 0.0;

    [[nodiscard]] const MethodRun* find(Method m) const;
    // cycles(ref) / cycles(method) under preset `preset`; 0 when not available.
    [[nodiscard]] double speedup(Method m, std::size_t preset = 0) const;
};

struct RunContext {
    unsigned threads = 0;
    bool quiet = false;
    std::string out_dir;  // rays/hits files are streamed here when requested
    WorkLimits limits;    // checked again once the scene is loaded
};

[[nodiscard]] RunResult run_simulation(const RunConfig& config, const nlohmann::json& effective,
                                       const RunContext& context);

}  // namespace rtc
