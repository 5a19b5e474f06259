// Compiles a method's ray path into a BuiltMethod. `Impl` provides
//   using Structures = ...;                       // what build() produced
//   static StructureCounts count(const Structures&);
//   static std::size_t bytes(const Structures&);
//   template <TraversalMode Mode, class Programs>
//   static TraceHit trace(const Structures&, Programs&, const Ray&);
// where Programs is a LeafPrograms (sim/hardware/leaf_programs.h): trace()
// calls programs.begin(), then programs.triangle()/custom() for each leaf its
// traversal reaches, then returns programs.finish<Mode>(ray). The adapter
// instantiates trace() for every primitive kind and traversal mode and picks
// the instantiation once per frame.
#pragma once

#include "sim/execution/frame.h"
#include "sim/methods/method.h"

#include <span>
#include <utility>

namespace rtc {

template <class Impl>
class BuiltMethodOf final : public BuiltMethod {
public:
    explicit BuiltMethodOf(typename Impl::Structures s) : s_(std::move(s)) {}

    [[nodiscard]] StructureCounts structures() const override { return Impl::count(s_); }
    [[nodiscard]] std::size_t simulator_bytes() const override { return Impl::bytes(s_); }

    [[nodiscard]] FrameResult run(const Geometry& g, const RayWorkload& workload,
                                  const TraceOptions& options,
                                  const FrameOptions& frame) const override {
        return std::visit(
            [&](const auto& prims) {
                using Prim = typename std::decay_t<decltype(prims)>::value_type;
                // Spans made once per frame: from the vectors, per ray, each
                // cost a size computation (a division by the element size).
                const std::span<const Prim> p(prims);
                const std::span<const Triangle> triangles(g.triangles);
                // One LeafPrograms per frame task (its sink and scratch are the
                // task's), not per ray: made per ray it cost 7 stores each.
                // `record_calls` (std::true_type for the warp runner) makes
                // a second instantiation that records each program call.
                return run_frame(workload, frame, [&](CountingSink& sink, TraceScratch& scratch, auto record_calls) {
                    using Programs = LeafPrograms<Prim, CountingSink, decltype(record_calls)::value>;
                    return [this, programs = Programs(p, triangles, options, scratch, sink)](const Ray& ray) mutable {
                        return Impl::template trace<TraversalMode::Closest>(s_, programs, ray);
                    };
                });
            },
            g.prims);
    }

    [[nodiscard]] TraceHit trace(const Geometry& g, const Ray& ray, const TraceOptions& options,
                                 CountingSink& sink, TraversalMode mode) const override {
        TraceScratch scratch;
        return std::visit(
            [&](const auto& prims) {
                using Prim = typename std::decay_t<decltype(prims)>::value_type;
                LeafPrograms<Prim, CountingSink> programs(std::span<const Prim>(prims), g.triangles,
                                                          options, scratch, sink);
                switch (mode) {
                    case TraversalMode::AnyHit:
                        return Impl::template trace<TraversalMode::AnyHit>(s_, programs, ray);
                    case TraversalMode::AllCandidates:
                        return Impl::template trace<TraversalMode::AllCandidates>(s_, programs, ray);
                    case TraversalMode::Closest: break;
                }
                return Impl::template trace<TraversalMode::Closest>(s_, programs, ray);
            },
            g.prims);
    }

private:
    typename Impl::Structures s_;
};

}  // namespace rtc
