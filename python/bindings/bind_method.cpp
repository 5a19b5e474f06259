// One method of a traced run: its totals, priced runs and memory, and its
// per-pixel data as NumPy views (no copy; the arrays keep the run alive).
// Per-pixel float fields are listed once in kPixelFields, so a new one (the
// SIMT model adds them) is one line.
#include "common.h"
#include "priced.h"

#include "sim/methods/method.h"
#include "sim/run/simulation.h"  // price_preset

#include <stdexcept>

namespace rtc::py_bind {

namespace {

static_assert(sizeof(RayCounts) == kEventCount * sizeof(std::uint32_t), "RayCounts must be packed counts");
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
static_assert(sizeof(Ray) == 32 && sizeof(TraceHit) == 28, "Ray / TraceHit layouts changed: update the dtypes");

// Per-pixel float fields of FrameResult, (H, W) each; empty unless recorded.
struct PixelField {
    const char* name;
    const std::vector<float>& (*field)(const FrameResult&);
    const char* doc;
};
const std::vector<float> kNoPixels;
const PixelField kPixelFields[] = {
    {"pixel_warp_cycles",
     [](const FrameResult& f) -> const std::vector<float>& { return f.warp.empty() ? kNoPixels : f.warp.front().pixel_cycles; },
     "Warp model, first warp preset: each pixel's share of its waves' cycles."},
    {"pixel_simt_active", [](const FrameResult& f) -> const std::vector<float>& { return f.pixel_simt_active; },
     "Warp model: active lane-rounds of each pixel's waves."},
    {"pixel_simt_slots", [](const FrameResult& f) -> const std::vector<float>& { return f.pixel_simt_slots; },
     "Warp model: rounds x warp width of each pixel's waves."},
};

py::object handle_of(const MethodHandle& h) { return keep_alive(h.run); }

py::dict memory_dict(const MemoryBreakdown& mem) {
    py::dict d;
    d["tlas_nodes"] = mem.tlas_nodes;
    d["blas_nodes"] = mem.blas_nodes;
    d["instances"] = mem.instances;
    d["custom_prims"] = mem.custom_prims;
    d["triangles"] = mem.triangles;
    d["acceleration"] = mem.acceleration();
    d["common"] = mem.common;
    d["total"] = mem.total();
    return d;
}

py::dict structures_dict(const StructureCounts& s) {
    py::dict d;
    d["width"] = s.width;
    d["tlas_nodes"] = s.tlas_nodes;
    d["blas_nodes"] = s.blas_nodes;
    d["instances"] = s.instances;
    d["custom_prims"] = s.custom_prims;
    d["triangles"] = s.triangles;
    return d;
}

// `model` applied to the method's counts; under a warp preset, to its
// recorded waves (the run must have been traced with record_warps and the
// preset must group rays as the run did). A sampled run's are scaled to the
// whole frame, as the run's own presets are.
Priced reprice(const MethodHandle& h, const CostModel& model) {
    const MethodRun& m = h.method();
    if (!m.runnable) throw std::invalid_argument(m.method + " was not run: " + m.reason);
    std::optional<WarpTotals> waves;
    if (model.execution.warp()) {
        if (m.frame.warp_trace.waves() == 0)
            throw std::invalid_argument(model.name + " is a warp preset: re-pricing needs the waves, "
                                        "so trace with record_warps=True and a warp preset in the run");
        if (!h.run->warp_grouping || !h.run->warp_grouping->same_grouping(model.execution))
            throw std::invalid_argument(model.name + " groups rays into other warps than the run traced");
        py::gil_scoped_release release;
        waves = m.frame.warp_trace.price(model);
    }
    // The run's own per-preset step (sim/run/simulation.h), so the totals
    // are what report.json would have (a sampled run's scaled to the frame).
    const MethodEntry* e = find_method(m.method);
    PresetPrice priced = price_preset(m.frame.totals, model, waves ? &*waves : nullptr, h.run->config,
                                      e ? e->info.needs : std::vector<std::string>{},
                                      h.run->sample ? h.run->sample->k() : 1);
    Priced p;
    p.run = std::move(priced.run);
    p.roof = priced.roof;
    if (waves) {
        p.warp = priced.warp;
        p.warp_width = model.execution.warp_width;
    }
    return p;
}

}  // namespace

void bind_method(py::module_& m) {
    auto cls = py::class_<MethodHandle>(m, "MethodRun", "One method of a traced run.");
    cls.def_property_readonly("name", [](const MethodHandle& h) { return h.method().method; })
        .def_property_readonly("runnable", [](const MethodHandle& h) { return h.method().runnable; })
        .def_property_readonly("reason", [](const MethodHandle& h) { return h.method().reason; })
        .def_property_readonly("instances", [](const MethodHandle& h) { return h.method().instances; })
        .def_property_readonly("rays_traced", [](const MethodHandle& h) { return h.method().frame.rays_traced; })
        .def_property_readonly("width", [](const MethodHandle& h) { return h.method().frame.width; })
        .def_property_readonly("height", [](const MethodHandle& h) { return h.method().frame.height; })
        .def_property_readonly("totals", [](const MethodHandle& h) {
            return view<std::uint64_t>(h.method().frame.totals.n.data(), {static_cast<py::ssize_t>(kEventCount)},
                                       handle_of(h));
        }, "Event totals over the frame (uint64, EVENT_NAMES order).")
        .def_property_readonly("pixel_counts", [](const MethodHandle& h) {
            const FrameResult& f = h.method().frame;
            const py::ssize_t rows = f.pixel_counts.empty() ? 0 : f.height, cols = f.pixel_counts.empty() ? 0 : f.width;
            return view<std::uint32_t>(f.pixel_counts.data(), {rows, cols, static_cast<py::ssize_t>(kEventCount)},
                                       handle_of(h));
        }, "Per-pixel event counts, summed over samples and bounces: (H, W, events) uint32.")
        .def_property_readonly("radiance", [](const MethodHandle& h) {
            const FrameResult& f = h.method().frame;
            const py::ssize_t rows = f.radiance.empty() ? 0 : f.height, cols = f.radiance.empty() ? 0 : f.width;
            return view<float>(f.radiance.data(), {rows, cols, 3}, handle_of(h));
        }, "Per-pixel radiance, mean over samples: (H, W, 3) float32 (linear).")
        .def_property_readonly("rays", [](const MethodHandle& h) {
            const std::vector<Ray>& r = h.method().frame.rays;
            const py::object f3 = py::make_tuple("<f4", 3);
            return record_view(r.data(), r.size(), sizeof(Ray),
                               {{"origin", f3, offsetof(Ray, origin)}, {"tmin", py::str("<f4"), offsetof(Ray, tmin)},
                                {"direction", f3, offsetof(Ray, direction)}, {"tmax", py::str("<f4"), offsetof(Ray, tmax)}},
                               handle_of(h));
        }, "Every traced ray (structured array), when the run kept them (rays=True).")
        .def_property_readonly("hits", [](const MethodHandle& h) {
            const std::vector<TraceHit>& r = h.method().frame.hits;
            return record_view(r.data(), r.size(), sizeof(TraceHit),
                               {{"t", py::str("<f4"), offsetof(TraceHit, t)},
                                {"normal", py::make_tuple("<f4", 3), offsetof(TraceHit, normal)},
                                {"u", py::str("<f4"), offsetof(TraceHit, u)},
                                {"prim", py::str("<u4"), offsetof(TraceHit, prim)},
                                {"geom", py::str("<u4"), offsetof(TraceHit, geom)}},
                               handle_of(h));
        }, "Every traced ray's closest hit (geom 0 curves, 1 triangles, 0xFFFFFFFF none), when kept.")
        .def_property_readonly("priced", [](const MethodHandle& h) {
            const MethodRun& r = h.method();
            std::vector<Priced> out;
            for (std::size_t p = 0; p < r.priced.size(); ++p) {
                Priced x{r.priced[p], std::nullopt, h.run->costs[p].execution.warp_width, {}};
                if (r.priced[p].execution == ExecutionKind::Warp && p < r.warp.size()) x.warp = r.warp[p];
                if (p < r.roof.size()) x.roof = r.roof[p];
                out.push_back(x);
            }
            return out;
        }, "One PricedRun per cost preset of the run, in config order.")
        .def_property_readonly("memory", [](const MethodHandle& h) { return memory_dict(h.method().memory); },
                               "Modelled memory in bytes, by part.")
        .def_property_readonly("structures", [](const MethodHandle& h) {
            return structures_dict(h.method().structures);
        })
        .def_property_readonly("build_seconds", [](const MethodHandle& h) { return h.method().build_seconds; })
        .def_property_readonly("trace_seconds", [](const MethodHandle& h) { return h.method().frame.trace_seconds; })
        .def_property_readonly("recorded_waves", [](const MethodHandle& h) {
            return h.method().frame.warp_trace.waves();
        }, "Waves kept for re-pricing under warp presets (record_warps=True).")
        .def("pixel_warp_cycles_of", [](const MethodHandle& h, const std::string& preset) {
            const FrameResult& fr = h.method().frame;
            const PresetWarp* w = fr.warp_of(preset);
            if (!w) throw py::value_error("\"" + preset + "\" is not a warp preset of this run");
            const std::vector<float>& v = w->pixel_cycles;
            const py::ssize_t rows = v.empty() ? 0 : fr.height, cols = v.empty() ? 0 : fr.width;
            return view<float>(v.data(), {rows, cols}, handle_of(h));
        }, py::arg("preset"),
             "Warp model: each pixel's share of its waves' cycles under the warp preset named `preset` "
             "(empty for ray lists, and for presets re-priced from recorded waves).")
        .def("price", &reprice, py::arg("model"),
             "Re-prices the traced counts (or, under a warp preset, the recorded waves) without tracing.");
    for (const PixelField& f : kPixelFields) {
        const auto field = f.field;
        cls.def_property_readonly(f.name, [field](const MethodHandle& h) {
            const FrameResult& fr = h.method().frame;
            const std::vector<float>& v = field(fr);
            const py::ssize_t rows = v.empty() ? 0 : fr.height, cols = v.empty() ? 0 : fr.width;
            return view<float>(v.data(), {rows, cols}, handle_of(h));
        }, f.doc);
    }
}

}  // namespace rtc::py_bind
