// The streaming multiprocessor (SM) around the warps: how many warps it keeps
// resident, and so how much of each wave's latency other warps hide.
//
// The warp model (warp_pricing.h) prices each wave as if it ran alone: its
// shader, RT-unit wait, hand-offs and program rounds add up to the wave's
// latency L_w. A real SM interleaves the N warps it holds resident, so over a
// frame it is bound by whichever of three resources runs out first (a
// roofline per SM; the form of Hong and Kim, ISCA 2009, "An Analytical Model
// for a GPU Architecture with Memory-level and Thread-level Parallelism
// Awareness": latency hidden by the warps in flight, or issue-bound):
//
//   latency:  sum_w L_w / N, with each program round's latency
//             latency_per_issue x its issue cycles (a call is a chain of
//             dependent operations);
//   issue:    sum_w P_w, the program rounds' issue cycles at the CUDA
//             Programming Guide's throughput prices (the op_* costs);
//   RT unit:  sum_w (sum over lanes of their RT-unit cycles) / rt_unit_lanes,
//             the unit shared by all of the SM's warps.
//
// N follows from the pipeline's register footprint: OptiX compiles ray
// generation, shading and every intersection program into one kernel, so a
// thread holds what that kernel needs (measured per pipeline with ptxas for
// sm_75: scripts/registers/measure), and an SM fits
// partitions x floor(registers_per_sm / partitions / (32 x registers rounded
// up to the allocation unit)) warps, at most max_warps (the CUDA Occupancy
// Calculator's rules, cuda_occupancy.h; CC 7.5: 64 K registers in 4
// sub-partitions, 32 warps). A long program with many live registers lowers N,
// and with it the latency hiding of the whole pipeline.
//
// A preset without an "sm" block keeps the lone-wave sum (every term added,
// as before the SM existed). Sources of each number: the preset's entries
// and docs/execution-model.md, "The SM".
#pragma once

#include "intersectors/kinds.h"
#include "intersectors/phantom_curve.h"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rtc {

class JsonReader;

// A preset's execution.sm block.
struct SmModel {
    bool enabled = false;
    int registers_per_sm = 65536;  // 32-bit registers of one SM
    int max_warps = 32;            // resident warps per SM at most
    int allocation_unit = 256;     // registers are allocated per warp in units of this many
    int partitions = 4;            // sub-partitions, each with its own share of the register file
    // Registers per thread of each pipeline, as the compiler allocated them
    // for the one kernel of ray generation, shading and the named
    // intersection program ("shader": a pipeline without one).
    std::vector<std::pair<std::string, int>> registers;
    double latency_per_issue = 1.0;  // a program's latency per issue cycle
    double rt_unit_lanes = 1.0;      // rays the RT unit serves at once, over all warps
    std::vector<std::pair<std::string, std::string>> sources;  // key -> provenance

    // Registers per thread of `program`'s pipeline (empty: a pipeline
    // without an intersection program, "shader"). Throws
    // std::invalid_argument naming a pipeline not listed.
    [[nodiscard]] int pipeline_registers(std::string_view program) const;
};

// The SM resources a frame's waves are priced against, for one pipeline.
struct Roofline {
    bool enabled = false;  // false: the lone-wave sum
    int warps = 1;         // resident warps N
    int registers = 0;     // per thread, the pipeline's
    double latency_per_issue = 1.0;
    double rt_unit_lanes = 1.0;
};

// Resident warps for `registers` per thread: each sub-partition's share of
// the register file holds whole warps (their registers rounded up to the
// allocation unit), at most max_warps in all.
[[nodiscard]] int resident_warps(const SmModel& sm, int registers, int warp_width);

// The roofline of `program`'s pipeline under `sm` (disabled when sm is).
[[nodiscard]] Roofline roofline(const SmModel& sm, std::string_view program, int warp_width);

// The intersection program a pipeline compiles in: the kind's name
// ("capsule", ...; phantom curves "phantom_paper" or "phantom_bracketed"), or
// empty for a method that runs none (its primitives tested in the RT unit).
[[nodiscard]] std::string pipeline_program(PrimitiveKind kind, PhantomProgram program, bool runs_programs);

// Reads an "sm" block: {"enabled": {"value": false, "source"} (turns a
// base preset's SM off; the other keys are then not read), "registers_per_sm": {"value", "source"}, "max_warps",
// "allocation_unit", "partitions", "registers": {"value": {"shader": n, "<program>": n,
// ...}, "source"}, "latency_per_issue", "rt_unit_lanes"}; keys absent keep
// `base`'s values (a derived preset's block overrides its base's key by key).
[[nodiscard]] SmModel parse_sm_model(const JsonReader& block, const SmModel& base = {});

}  // namespace rtc
