// The seam between a way of putting primitives on RT hardware (a "method")
// and everything else. A method is one file (ref.cpp, obb.cpp, ...) that
// returns a MethodEntry: its name and what it needs from the hardware preset,
// how many TLAS instances it will need (checked against the hardware limit
// before building), and how to build its structures from a Geometry. The
// built method reports the records the memory model prices and runs a
// workload through its own ray path: a template instantiated per method and
// primitive kind, entered through one virtual call per frame, never per ray.
//
// Adding a method: write sim/methods/<name>.cpp (see ref.cpp for the pattern
// and common/method_adapter.h for the template that compiles its ray path) and add
// one line to the list in registry.cpp. Code outside the tree (tests, a
// researcher's experiment) can add one at run time with register_method().
#pragma once

#include "core/bvh.h"
#include "core/sinks.h"
#include "core/traverse.h"
#include "intersectors/kinds.h"
#include "sim/execution/frame_result.h"
#include "sim/hardware/leaf_programs.h"
#include "sim/hardware/memory_model.h"
#include "sim/methods/common/geometry.h"

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

// How `cluster` groups primitives and frames each group (config block
// "cluster", configs/README.md; cluster_groups.h says what each choice costs).
enum class ClusterStrategy : std::uint8_t { Strand, Orientation };
enum class ClusterFrame : std::uint8_t { Best, Principal };
struct ClusterOptions {
    ClusterStrategy strategy = ClusterStrategy::Orientation;
    int size = 16;  // primitives per cluster (at most; see cluster_groups.h)
    ClusterFrame frame = ClusterFrame::Best;
};

struct MethodOptions {
    BuildOptions custom_blas;     // leaf size 1: one box per custom primitive
    BuildOptions triangle_blas;   // triangles may share leaves
    BuildOptions tlas;            // leaf size 1: one box per instance
    ObbVariant obb = ObbVariant::Paper;
    ClusterOptions cluster;       // only the cluster method reads it
    // The oriented-node methods (obb-nodes, obb-quantized) orient the
    // triangle BLAS too, as GPURT does on RDNA4 (config bvh.oriented_triangles;
    // off: the mesh BLAS is ref's, as before).
    bool oriented_triangles = false;
};

struct MethodInfo {
    std::string name;                // in configs and reports
    std::string summary;             // one line, for --help and the docs
    // Hardware features the method relies on; a cost preset without one of
    // them prices the method as n/a (see CostModel::features).
    std::vector<std::string> needs;
    // Its hits approximate the primitives' (dots: triangles stand in for
    // curves) instead of being ref's bit for bit: a run reports its hit
    // agreement with the baseline (sim/run/hit_agreement.h), and the tests
    // that require identical hits leave it out.
    bool approximate = false;
};

// A method's structures, built for one geometry.
class BuiltMethod {
public:
    virtual ~BuiltMethod() = default;
    // What the memory model prices.
    [[nodiscard]] virtual StructureCounts structures() const = 0;
    // The simulator's own bytes for these structures (not the modelled hardware's).
    [[nodiscard]] virtual std::size_t simulator_bytes() const = 0;
    // Traces a whole workload (closest hits) on all cores.
    [[nodiscard]] virtual FrameResult run(const Geometry& geometry, const RayWorkload& workload,
                                          const TraceOptions& trace,
                                          const FrameOptions& frame) const = 0;
    // Traces one ray in any traversal mode (tests and tools).
    [[nodiscard]] virtual TraceHit trace(const Geometry& geometry, const Ray& ray,
                                         const TraceOptions& trace, CountingSink& sink,
                                         TraversalMode mode = TraversalMode::Closest) const = 0;
};

// A method's own share of the simulator's peak memory, for the work estimate
// (sim/config/work_estimate.h) before the scene is converted: the instances it
// will build (a method over the preset's instance limit is not built, so
// costs nothing) and the bytes its structures and their build take beyond
// the per-primitive figure every method shares. Upper bounds, from measured
// peaks (each method's file says which).
struct MethodFootprint {
    double instances = 1.0;
    double bytes = 0.0;
};

struct MethodEntry {
    MethodInfo info;
    // May depend on the options (a method that groups primitives into instances).
    std::function<std::uint64_t(const Geometry&, const MethodOptions&)> instance_count;
    // Throws std::invalid_argument on a primitive whose bounds are not finite.
    std::function<std::unique_ptr<BuiltMethod>(const Geometry&, const MethodOptions&)> build;
    // Optional: why the method cannot represent this geometry (e.g. a
    // hardware primitive that only fits some kinds), or empty when it can.
    // A run reports such a method as n/a with that reason; build() throws.
    std::function<std::string(const Geometry&)> not_applicable = nullptr;
    // Optional: the method's footprint over `primitives` primitives in
    // `strands` strands (0 for a mesh); unset: one instance, no bytes of its own.
    std::function<MethodFootprint(double primitives, double strands, const MethodOptions&)> footprint = nullptr;
};

// The reason `entry` cannot run on `g`, or empty.
[[nodiscard]] std::string not_applicable_reason(const MethodEntry& entry, const Geometry& g);

// Every method, built-in ones first, in registration order.
[[nodiscard]] const std::vector<MethodEntry>& registered_methods();
// nullptr when no method has that name.
[[nodiscard]] const MethodEntry* find_method(std::string_view name);
// Adds a method; throws std::invalid_argument when the name is taken or empty.
void register_method(MethodEntry entry);
// "ref, obb, ..." for error messages and --help.
[[nodiscard]] std::string method_names_list();

}  // namespace rtc
