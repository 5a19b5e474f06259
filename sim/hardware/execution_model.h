// How the hardware executes rays, selected in the hardware (cost) preset:
//
// per_ray: every ray's events priced on their own and summed (the model of
//          the first version: no divergence, no lockstep).
// warp:    SIMT. Rays run in warps of W lanes (camera workloads: a pixel tile
//          at one sample index, bounce k of its paths is the warp's k-th
//          wave; ray files: W consecutive rays). Per wave:
//            shader work (event unit Shader) once: the lanes run in lockstep;
//            RT-unit work per lane, combined as max(slowest lane, sum / P):
//              P = rt_parallel_lanes lanes' traversals overlap in the unit
//              (P = 1: throughput-bound, a sum; P = W: latency-bound, the
//              slowest lane);
//            intersection programs in rounds: round r serves each lane's r-th
//              candidate and costs one hand-off (context switch) plus the most
//              expensive active lane's program (its own events priced).
//          A preset can name RT-unit events that its machine runs as shader
//          code in the wave's own traversal loop (AMD RDNA: the loop, its
//          stack and instance transforms are shader instructions, only the
//          node tests are ray-accelerator instructions): those are priced in
//          lockstep, the wave paying its slowest lane's, like shader work.
// The formulas and their sources: docs/execution-model.md.
#pragma once

#include "core/events.h"
#include "sim/hardware/sm_model.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rtc {

class JsonReader;

enum class ExecutionKind : std::uint8_t { PerRay, Warp };

struct ExecutionModel {
    ExecutionKind kind = ExecutionKind::PerRay;
    int warp_width = 32;           // lanes per warp
    int tile_width = 8, tile_height = 4;  // the pixel tile a camera warp covers
    double rt_parallel_lanes = 32; // lanes whose RT-unit work overlaps (1..W)
    // RT-unit events this machine runs as shader code in lockstep (empty on
    // NVIDIA, whose RT core traverses on its own), in the preset's order.
    [[nodiscard]] const std::vector<Event>& lockstep_events() const { return lockstep_; }
    // Sets them, and places them in unit(): the one place they are applied.
    void set_lockstep_events(std::vector<Event> events);
    // Each event's unit on this machine, computed when the preset is loaded:
    // its kEventUnits entry, except that the lockstep events are
    // EventUnit::Lockstep. Pricers ask this, not kEventUnits and the list.
    [[nodiscard]] EventUnit unit(Event e) const { return units_[static_cast<std::size_t>(e)]; }
    // The BVH node width this machine's driver builds (AMD GPURT / RADV:
    // 4-wide on RDNA2/3, 8-wide on RDNA4); 0: not public, the run's
    // bvh.width decides. A run takes its presets' width (sim/config).
    int bvh_width = 0;
    // The SM around the warps (sm_model.h): resident warps hide latency.
    // Disabled: each wave priced alone and summed.
    SmModel sm;
    std::vector<std::pair<std::string, std::string>> sources;  // key -> provenance

    [[nodiscard]] bool warp() const { return kind == ExecutionKind::Warp; }
    // Same warp grouping (so one traced frame serves both presets).
    [[nodiscard]] bool same_grouping(const ExecutionModel& o) const {
        return warp_width == o.warp_width && tile_width == o.tile_width && tile_height == o.tile_height;
    }

private:
    std::vector<Event> lockstep_;
    std::array<EventUnit, kEventCount> units_ = [] {
        std::array<EventUnit, kEventCount> u{};
        for (std::size_t e = 0; e < kEventCount; ++e) u[e] = kEventUnits[e];
        return u;
    }();
};

// Reads the optional "execution" block of a cost preset:
// {"model": {"value": "warp", "source": ...}, "warp_width": {...},
//  "tile": {"value": [8, 4], ...}, "rt_parallel_lanes": {...},
//  "lockstep_events": {"value": ["tlas_node_visit", ...], ...},
//  "bvh_width": {"value": 2, 4 or 8, ...}, "sm": {...} (parse_sm_model)}.
// Keys absent from the block keep `base`'s values (a derived preset's
// execution block overrides its base's key by key).
[[nodiscard]] ExecutionModel parse_execution_model(const JsonReader& block, const ExecutionModel& base = {});

[[nodiscard]] const char* execution_name(ExecutionKind k);

}  // namespace rtc
