// The vocabulary of hardware and software events a traced ray produces.
//
// Traversal and intersectors report what happened (`sink.on(Event::X)`); what
// it costs is decided later by pricing the counts (sim/cost_model.h). One enum
// entry per event with a parallel name table: configs refer to events by name.
#pragma once

#include "core/enum_names.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace rtc {

enum class Event : std::uint8_t {
    Ray,                 // one traced ray: fixed cost of generation and shading
    TlasNodeVisit,       // a TLAS node is fetched
    TlasBoxTest,         // one child box of a TLAS node is tested
    InstanceTransform,   // the ray is transformed into an instance's object space
    BlasNodeVisit,       // a BLAS node is fetched
    BlasBoxTest,         // one child box of a BLAS node is tested
    TriangleTest,        // a hardware ray/triangle test
    ContextSwitch,       // a custom-primitive leaf box was hit: hand-over to the SM
    IsCall,              // an intersection program runs (any kind)
    IsCylinder,          // ... the cylinder program (base cost)
    IsCapsule,           // ... the capsule program
    IsLink,              // ... the link (cone stump + spheres) program
    IsPhantom,           // ... a phantom curve program (either; counts calls): entry, curve fetch
    PhantomSetup,        // the ray-centric frame: direction basis, 4 control points transformed
    PhantomIteration,    // bracketed program: one iteration of its root finder
    PhantomEarlyOut,     // bracketed program: its bounding-cylinder early-out test ran
    PhantomEarlyReject,  // ... and rejected the ray before iterating
    PhantomBracketTest,  // bracketed program: one ray/capsule test bounding a sub-curve
    PhantomCylinderTest, // paper program: the capped bounding-cylinder early out (world space)
    PhantomPaperIteration,  // paper program: one Reshetov & Luebke iteration (tangent cone)
    PhantomSecondEnd,    // paper program: the first end's search failed, restart at the other
    ReportedHit,         // an intersection program reported a hit
    LeafObbTest,         // software OBB test at the start of an IS program (Embree curveNi-style)
    LssTest,             // hardware ray/linear-swept-sphere test in the RT unit (Blackwell)
    ObbBoxTest,          // hardware test of one oriented child box (own 3x4 transform, Woop et al. 2014)
    NodeRotate,          // the ray is rotated once for a node whose children share a rotation (RDNA4)
    // What an intersection program executed, by operation class (core/ops.h),
    // counted on the path each call took: a calibrated preset prices these,
    // not the programs by name.
    OpFma,               // FP32 add, multiply, fused multiply-add, min/max/abs
    OpDiv,               // a division (or reciprocal)
    OpSqrt,              // a square root or reciprocal square root
    OpBranch,            // a compare-and-branch (a test that can end the call or pick a path)
    OpLoad,              // a 16-byte load of primitive data
    Count
};

inline constexpr std::size_t kEventCount = static_cast<std::size_t>(Event::Count);

inline constexpr std::array<std::string_view, kEventCount> kEventNames = {
    "ray",           "tlas_node_visit",   "tlas_box_test",        "instance_transform",
    "blas_node_visit", "blas_box_test",   "triangle_test",        "context_switch",
    "is_call",       "is_cylinder",       "is_capsule",           "is_link",
    "is_phantom",    "phantom_setup",     "phantom_iteration",    "phantom_early_out",
    "phantom_early_reject", "phantom_bracket_test", "phantom_cylinder_test",
    "phantom_paper_iteration", "phantom_second_end", "reported_hit", "leaf_obb_test",
    "lss_test",      "obb_box_test",      "node_rotate",
    "op_fma",        "op_div",            "op_sqrt",              "op_branch",
    "op_load",
};

static_assert(!kEventNames.back().empty(), "every Event needs a name in kEventNames");

// Where an event's work happens, which decides how a warp combines it (the
// SIMT execution model, sim/execution/warp.h):
// Shader:  the ray's own SM work (generation, shading): all lanes in lockstep.
// RtUnit:  traversal work in the RT unit, per lane.
// HandOff: the RT unit handing a candidate to the SM (once per IS round).
// Program: work inside an intersection program, per call; a round costs the
//          most expensive active lane's program.
// Lockstep: RT-unit work that a machine runs as shader code in the wave's own
//          traversal loop (AMD RDNA), so the wave pays its slowest lane's. No
//          event has it in kEventUnits: a preset moves RT-unit events there
//          (ExecutionModel::unit, sim/hardware/execution_model.h).
enum class EventUnit : std::uint8_t { Shader, RtUnit, HandOff, Program, Lockstep };

inline constexpr EventUnit kEventUnits[] = {
    EventUnit::Shader,   // ray
    EventUnit::RtUnit,   // tlas_node_visit
    EventUnit::RtUnit,   // tlas_box_test
    EventUnit::RtUnit,   // instance_transform
    EventUnit::RtUnit,   // blas_node_visit
    EventUnit::RtUnit,   // blas_box_test
    EventUnit::RtUnit,   // triangle_test
    EventUnit::HandOff,  // context_switch
    EventUnit::Program,  // is_call
    EventUnit::Program,  // is_cylinder
    EventUnit::Program,  // is_capsule
    EventUnit::Program,  // is_link
    EventUnit::Program,  // is_phantom
    EventUnit::Program,  // phantom_setup
    EventUnit::Program,  // phantom_iteration
    EventUnit::Program,  // phantom_early_out
    EventUnit::Program,  // phantom_early_reject
    EventUnit::Program,  // phantom_bracket_test
    EventUnit::Program,  // phantom_cylinder_test
    EventUnit::Program,  // phantom_paper_iteration
    EventUnit::Program,  // phantom_second_end
    EventUnit::Program,  // reported_hit
    EventUnit::Program,  // leaf_obb_test: software, at the start of the program
    EventUnit::RtUnit,   // lss_test
    EventUnit::RtUnit,   // obb_box_test
    EventUnit::RtUnit,   // node_rotate
    EventUnit::Program,  // op_fma
    EventUnit::Program,  // op_div
    EventUnit::Program,  // op_sqrt
    EventUnit::Program,  // op_branch
    EventUnit::Program,  // op_load
};

static_assert(std::size(kEventUnits) == kEventCount, "every Event needs a unit in kEventUnits");

// How a preset prices intersection programs: either by name (a cost per
// program event, the first version's guesses) or by what they executed (a
// cost per operation class, so a cheap early reject is cheap and phantom
// iterations add up). A preset prices exactly one of these two groups; the
// other group's events are still counted (calls per kind, iterations) but
// cost nothing under it.
[[nodiscard]] constexpr bool is_operation_event(Event e) {
    return e >= Event::OpFma && e <= Event::OpLoad;
}
[[nodiscard]] constexpr bool is_program_name_event(Event e) {
    return (e >= Event::IsCylinder && e <= Event::PhantomSecondEnd) || e == Event::LeafObbTest;
}

// The events of unit U (with `Others`, of every unit but U) as indices in
// enum order: the one list pricing (sim/hardware/warp_pricing.cpp), a
// recorded wave's lanes (warp_trace.cpp) and a call's program profile
// (call_profiles.h) iterate, so an event's unit is said in kEventUnits only.
template <EventUnit U, bool Others = false>
[[nodiscard]] constexpr auto events_of_unit() {
    constexpr std::size_t n = [] {
        std::size_t k = 0;
        for (const EventUnit u : kEventUnits) k += (u == U) != Others;
        return k;
    }();
    std::array<std::uint8_t, n> idx{};
    std::size_t k = 0;
    for (std::size_t e = 0; e < kEventCount; ++e)
        if ((kEventUnits[e] == U) != Others) idx[k++] = static_cast<std::uint8_t>(e);
    return idx;
}

[[nodiscard]] constexpr EventUnit event_unit(Event e) {
    return kEventUnits[static_cast<std::size_t>(e)];
}

[[nodiscard]] constexpr std::string_view event_name(Event e) {
    return kEventNames[static_cast<std::size_t>(e)];
}

[[nodiscard]] constexpr std::optional<Event> event_from_name(std::string_view name) {
    return enum_from_name<Event>(kEventNames, name);
}

}  // namespace rtc
