// The methods for the hardware after Turing (leaf-obb, split, lss, obb-nodes,
// obb-quantized) return ref's closest hit for every ray (same primitive, same
// t bit for bit), for every primitive kind they accept, every BVH width, both
// IS schedules, with and without a mesh; and each does what it claims in the
// event counts (fewer programs, no hand-over, OBB tests, rotations).
#include "sim/hardware/cost_model.h"
#include "sim/methods_test_util.h"

#include <doctest/doctest.h>

#include <bit>
#include <filesystem>
#include <set>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using namespace rtc::test;

namespace {

// Every method that must return ref's hits bit for bit. dots is left out on
// purpose: its triangles approximate the curves (MethodInfo::approximate);
// test_methods_dots.cpp measures its agreement instead.
constexpr const char* kBeyond[] = {"leaf-obb", "split", "lss", "obb-nodes", "obb-quantized", "aabb-quantized"};

bool same_hit(const TraceHit& a, const TraceHit& b) {
    return a.geom == b.geom && a.prim == b.prim &&
           std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
}

struct Totals {
    EventTotals ref, method;
    int mismatches = 0, hits = 0;
};

Totals compare_with_ref(std::string_view name, PrimitiveKind kind, bool mesh, int width, int rays) {
    Rng rng(4000 + static_cast<int>(kind) * 10 + mesh * 3 + width);
    const Geometry g = random_geometry(rng, kind, 500, mesh);
    const auto ref = build("ref", g, options(width));
    const auto m = build(name, g, options(width));
    Totals t;
    for (int i = 0; i < rays; ++i) {
        const Ray ray = scene_ray(rng);
        for (const IsSchedule schedule : {IsSchedule::Immediate, IsSchedule::Deferred}) {
            CountingSink sr, sm;
            const TraceHit a = trace_any(ref, g, ray, sr, schedule);
            const TraceHit b = trace_any(m, g, ray, sm, schedule);
            t.mismatches += !same_hit(a, b);
            if (schedule == IsSchedule::Immediate) {
                t.hits += a.hit();
                t.ref.add(sr.ray);
                t.method.add(sm.ray);
            }
        }
    }
    return t;
}

bool lss_kind(PrimitiveKind k) { return k == PrimitiveKind::Capsule || k == PrimitiveKind::Link; }

}  // namespace

TEST_CASE("beyond: every new method returns ref's closest hit for every ray") {
    for (const char* name : kBeyond) {
        for (const PrimitiveKind kind : kKinds) {
            if (std::string_view(name) == "lss" && !lss_kind(kind)) continue;
            for (const bool mesh : {false, true}) {
                for (const int width : {2, 4, 8}) {
                    CAPTURE(name);
                    CAPTURE(kind_name(kind));
                    CAPTURE(mesh);
                    CAPTURE(width);
                    const Totals t = compare_with_ref(name, kind, mesh, width, kind == PrimitiveKind::Phantom ? 400 : 800);
                    CHECK(t.mismatches == 0);
                    CHECK(t.hits > 50);
                }
            }
        }
    }
}

TEST_CASE("beyond: the identical-hits lists hold every exact built-in method and leave the approximate ones out") {
    std::set<std::string> exact{"ref", "obb", "cluster"};  // ref and obb: test_methods.cpp; cluster: test_methods_curve_basis.cpp
    exact.insert(std::begin(kBeyond), std::end(kBeyond));
    for (const MethodEntry& m : registered_methods()) {
        if (m.info.name.rfind("test-", 0) == 0) continue;  // registered by other tests (test_method_seam.cpp)
        CAPTURE(m.info.name);
        CHECK(exact.count(m.info.name) == (m.info.approximate ? 0u : 1u));
    }
    CHECK(find_method("dots")->info.approximate);
}

TEST_CASE("beyond: leaf-obb pays ref's hand-overs, each an OBB test, and runs far fewer bodies") {
    for (const PrimitiveKind kind : kKinds) {
        CAPTURE(kind_name(kind));
        const Totals t = compare_with_ref("leaf-obb", kind, false, 4, 600);
        CHECK(t.method[Event::ContextSwitch] == t.ref[Event::ContextSwitch]);
        CHECK(t.method[Event::LeafObbTest] == t.method[Event::ContextSwitch]);
        CHECK(t.method[Event::IsCall] * 2 < t.ref[Event::IsCall]);
    }
}

TEST_CASE("beyond: split calls a program per reference reached, fewer in total than ref") {
    for (const PrimitiveKind kind : kKinds) {
        CAPTURE(kind_name(kind));
        const Totals t = compare_with_ref("split", kind, false, 4, 600);
        CHECK(t.method[Event::ContextSwitch] == t.method[Event::IsCall]);
        CHECK(t.method[Event::IsCall] < t.ref[Event::IsCall]);
    }
}

TEST_CASE("beyond: lss tests ref's candidates in the RT unit, with no hand-over") {
    for (const PrimitiveKind kind : {PrimitiveKind::Capsule, PrimitiveKind::Link}) {
        CAPTURE(kind_name(kind));
        const Totals t = compare_with_ref("lss", kind, false, 4, 600);
        CHECK(t.method[Event::ContextSwitch] == 0);
        CHECK(t.method[Event::IsCall] == 0);
        CHECK(t.method[Event::LssTest] == t.ref[Event::ContextSwitch]);  // same BLAS, same boxes
    }
}

TEST_CASE("beyond: obb-nodes tests oriented children and halves the programs") {
    for (const PrimitiveKind kind : kKinds) {
        CAPTURE(kind_name(kind));
        const Totals t = compare_with_ref("obb-nodes", kind, false, 4, 600);
        CHECK(t.method[Event::ObbBoxTest] > 0);
        CHECK(t.method[Event::NodeRotate] == 0);
        CHECK(t.method[Event::IsCall] * 2 < t.ref[Event::IsCall]);
    }
}

TEST_CASE("beyond: obb-quantized rotates the ray per node and calls fewer programs") {
    for (const PrimitiveKind kind : kKinds) {
        CAPTURE(kind_name(kind));
        const Totals t = compare_with_ref("obb-quantized", kind, false, 4, 600);
        CHECK(t.method[Event::NodeRotate] > 0);
        CHECK(t.method[Event::ObbBoxTest] == 0);
        CHECK(t.method[Event::IsCall] < t.ref[Event::IsCall]);
    }
}

TEST_CASE("beyond: lss is not applicable to cylinders and phantom curves, and says why") {
    Rng rng(5);
    const MethodEntry* lss = find_method("lss");
    REQUIRE(lss != nullptr);
    for (const PrimitiveKind kind : kKinds) {
        const Geometry g = random_geometry(rng, kind, 10, false);
        const std::string why = not_applicable_reason(*lss, g);
        CAPTURE(kind_name(kind));
        CHECK(why.empty() == lss_kind(kind));
        if (!why.empty()) {
            CHECK(why.find(kind_name(kind)) != std::string::npos);
            CHECK_THROWS_AS((void)lss->build(g, options(4)), std::invalid_argument);
        }
        CHECK(not_applicable_reason(*find_method("ref"), g).empty());
    }
}

TEST_CASE("beyond: structure counts the memory model prices") {
    Rng rng(9);
    const Geometry g = random_geometry(rng, PrimitiveKind::Capsule, 300, true);
    const StructureCounts ref = build("ref", g, options(4))->structures();
    const StructureCounts leaf = build("leaf-obb", g, options(4))->structures();
    CHECK(leaf.leaf_obbs == 300);
    CHECK(leaf.custom_prims == ref.custom_prims);
    const StructureCounts split = build("split", g, options(4))->structures();
    CHECK(split.custom_prims > ref.custom_prims);       // several references per long primitive
    CHECK(split.custom_prims <= 8 * ref.custom_prims);  // at most 8 pieces each
    const StructureCounts lss = build("lss", g, options(4))->structures();
    CHECK(lss.lss_prims == 300);
    CHECK(lss.custom_prims == 0);
    CHECK(lss.triangles == g.triangles.size());
    const StructureCounts nodes = build("obb-nodes", g, options(4))->structures();
    CHECK(nodes.oriented_children > 0);
    CHECK(nodes.custom_prims == 300);
    const StructureCounts quant = build("obb-quantized", g, options(4))->structures();
    CHECK(quant.oriented_children == 0);  // the rotation index lives in the node
    CHECK(quant.blas_nodes == ref.blas_nodes);
}

TEST_CASE("beyond: every hardware preset loads with a source per event and says what it can run") {
    namespace fs = std::filesystem;
    const std::set<std::string> known{"custom_primitives", "instance_transforms", "lss", "obb_nodes",
                                      "quantized_obb_nodes"};
    std::set<std::string> names, runnable;
    for (const auto& e : fs::directory_iterator(fs::path(RTCSIM_SOURCE_DIR) / "configs" / "hw")) {
        const std::string file = e.path().filename().string();
        if (e.path().extension() != ".json" || file.rfind("memory-", 0) == 0) continue;
        CAPTURE(file);
        const CostModel m = load_cost_model(e.path().string());
        names.insert(m.name);
        for (std::size_t i = 0; i < kEventCount; ++i) CHECK(m.source[i].size() > 10);
        for (const std::string& f : m.features) CHECK(known.count(f) == 1);
        for (const MethodEntry& method : registered_methods())
            if (m.missing_feature(method.info.needs).empty()) runnable.insert(method.info.name);
    }
    for (const char* gen : {"turing-calibrated", "ampere", "ada", "blackwell", "rdna3", "rdna4"})
        CHECK(names.count(gen) == 1);
    // Every built-in method runs under at least one preset.
    for (const char* m : {"ref", "obb", "leaf-obb", "split", "lss", "obb-nodes", "obb-quantized"})
        CHECK(runnable.count(m) == 1);
}

}  // namespace RTCSIM_TEST_FILE
