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
    IsPhantom,           // ... the phantom curve program (base cost)
    PhantomIteration,    // one iteration of the phantom root finder
    PhantomEarlyOut,     // the phantom bounding-cylinder early-out test ran
    PhantomEarlyReject,  // ... and rejected the ray before iterating
    PhantomBracketTest,  // one ray/capsule test bounding a sub-curve (root bracketing)
    ReportedHit,         // an intersection program reported a hit
    LeafObbTest,         // software OBB test at the start of an IS program (Embree curveNi-style)
    LssTest,             // hardware ray/linear-swept-sphere test in the RT unit (Blackwell)
    ObbBoxTest,          // hardware test of one oriented child box (own 3x4 transform, Woop et al. 2014)
    NodeRotate,          // the ray is rotated once for a node whose children share a rotation (RDNA4)
    Count
};

inline constexpr std::size_t kEventCount = static_cast<std::size_t>(Event::Count);

inline constexpr std::array<std::string_view, kEventCount> kEventNames = {
    "ray",           "tlas_node_visit",   "tlas_box_test",        "instance_transform",
    "blas_node_visit", "blas_box_test",   "triangle_test",        "context_switch",
    "is_call",       "is_cylinder",       "is_capsule",           "is_link",
    "is_phantom",    "phantom_iteration", "phantom_early_out",    "phantom_early_reject",
    "phantom_bracket_test", "reported_hit", "leaf_obb_test",      "lss_test",
    "obb_box_test",  "node_rotate",
};

static_assert(!kEventNames.back().empty(), "every Event needs a name in kEventNames");

[[nodiscard]] constexpr std::string_view event_name(Event e) {
    return kEventNames[static_cast<std::size_t>(e)];
}

[[nodiscard]] constexpr std::optional<Event> event_from_name(std::string_view name) {
    return enum_from_name<Event>(kEventNames, name);
}

}  // namespace rtc
