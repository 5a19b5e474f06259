// Work estimates and their ceilings (see work_estimate.h).
#include "sim/config/work_estimate.h"

#include "core/input_error.h"
#include "core/sinks.h"
#include "sim/config/run_config.h"
#include "sim/execution/tile_sample.h"
#include "scenes/convert.h"
#include "sim/methods/method.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <filesystem>

namespace rtc {

namespace {

// Measured peaks (GNU time, max RSS) of a 1,000,000-capsule bundle on an
// 8 x 8 image: 368 MB (capsules) and 403 MB (phantom), one method's
// structures at a time: primitives, BVH nodes, instances, build scratch.
constexpr double kBytesPerPrimitive = 420.0;
// Per pixel and method, kept until the images are written: the event counts
// and the radiance (measured: 169 MB for 10^6 pixels and two methods).
constexpr double kBytesPerPixel = sizeof(RayCounts) + 3 * sizeof(float) + 16.0;
constexpr double kBytesPerRecordedRay = 32.0 + 24.0;  // ray and hit, when written out
constexpr double kBytesPerFileRay = 32.0 + 16.0;      // a ray workload held in memory
// Each method's own share (obb's instances, cluster's BLASes) is the
// method's to say: MethodEntry::footprint (sim/methods/method.h).

}  // namespace

std::string count_text(double x) {
    char buf[64];
    if (x < 1e6)
        std::snprintf(buf, sizeof buf, "%.0f", x);
    else
        std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

namespace {

double procedural_primitives(const SceneDesc& scene, PrimitiveKind kind, std::string& key) {
    if (scene.type == SceneType::Bundle) {
        key = "/scene/count";
        return scene.bundle.count;
    }
    if (scene.type == SceneType::Hair) {
        key = "/scene/strands";
        // One per link, or per phantom curve (scenes/convert.h: curve_count).
        const double per_strand = kind == PrimitiveKind::Phantom
                                      ? static_cast<double>(curve_count(scene.hair.points_per_strand, scene.curve_basis))
                                      : scene.hair.points_per_strand - 1.0;
        return static_cast<double>(scene.hair.strands) * std::max(1.0, per_strand);
    }
    return 0.0;
}

// The largest of the methods' own footprints (method.h: MethodFootprint)
// over `primitives` in `strands`, with the method that has it; methods over
// the memory preset's instance limit are not built and count nothing.
std::pair<double, std::string> method_bytes(const RunConfig& c, double primitives, double strands) {
    std::pair<double, std::string> largest{0.0, ""};
    const double limit = c.memory ? static_cast<double>(c.memory->instance_limit) : INFINITY;
    for (const std::string& name : c.methods) {
        const MethodEntry* m = find_method(name);
        if (!m || !m->footprint) continue;
        const MethodFootprint f = m->footprint(primitives, strands, c.build);
        if (f.instances <= limit && f.bytes > largest.first) largest = {f.bytes, name};
    }
    return largest;
}

// Adds the methods' term to `e` (primitives set), naming it when it is the largest.
void add_method_bytes(const RunConfig& c, double strands, WorkEstimate& e) {
    const auto [bytes, method] = method_bytes(c, e.primitives, strands);
    e.memory_bytes += bytes;
    if (bytes > 0.0 && bytes >= 0.5 * e.memory_bytes) {
        e.memory_key = method == "cluster" ? "/cluster/size" : "/methods";
        e.memory_detail = method + "'s structures over " + count_text(e.primitives) + " primitives" +
                          (method == "cluster" ? " in clusters of " + std::to_string(c.build.cluster.size) : "");
    }
}

}  // namespace

double memory_ceiling(const WorkLimits& limits) {
    if (limits.max_memory > 0.0) return limits.max_memory;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page > 0) return 0.75 * static_cast<double>(pages) * static_cast<double>(page);
    return 16.0 * 1024 * 1024 * 1024;
}

std::string format_estimate_bytes(double bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6) {
        bytes /= 1024.0;
        ++u;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
    return buf;
}

std::optional<double> parse_byte_size(const std::string& text) {
    std::size_t used = 0;
    double x = 0.0;
    try {
        x = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    const std::string unit = text.substr(used);
    double scale = 1.0;
    if (!unit.empty() && unit != "B") {
        const std::string prefixes = "KMGT";
        const auto p = prefixes.find(static_cast<char>(std::toupper(static_cast<unsigned char>(unit[0]))));
        const std::string rest = unit.substr(1);
        if (p == std::string::npos || !(rest.empty() || rest == "B" || rest == "iB")) return std::nullopt;
        scale = std::pow(1024.0, static_cast<double>(p + 1));
    }
    x *= scale;
    if (!std::isfinite(x) || !(x > 0.0)) return std::nullopt;
    return x;
}

namespace {

// The break-even maps' work after tracing: every cell prices each compared
// method under the preset and under each of its draws (when the preset has
// a covariance to draw from).
void add_break_even(const RunConfig& c, WorkEstimate& e) {
    double largest = -1.0;
    for (std::size_t i = 0; i < c.break_even.size(); ++i) {
        const BreakEvenSpec& spec = c.break_even[i];
        bool drawn = false;
        for (const auto& cost : c.costs) drawn = drawn || (cost && cost->name == spec.preset && cost->uncertainty);
        const double models = 1.0 + (drawn ? std::max(c.uncertainty.draws, 0) : 0);
        const double methods = static_cast<double>(spec.methods.empty() ? c.methods.size() : spec.methods.size());
        const double cells = static_cast<double>(spec.cells) * spec.cells;
        const double prices = cells * models * methods;
        e.break_even += prices;
        if (prices > largest) {
            largest = prices;
            e.break_even_key = "/break_even/" + std::to_string(i) + "/cells";
            e.break_even_detail = std::to_string(spec.cells) + " x " + std::to_string(spec.cells) + " cells x " +
                                  count_text(models) + " cost model(s) x " + count_text(methods) + " method(s)";
        }
    }
}

}  // namespace

WorkEstimate estimate_config_work(const RunConfig& c) {
    WorkEstimate e;
    const double methods = static_cast<double>(c.methods.size());
    const WorkloadDesc& w = c.workload;
    double pixels = 0.0;
    if (w.type == WorkloadType::Rays) {
        std::error_code ec;
        const auto size = std::filesystem::file_size(w.rays_file, ec);
        const double rays = ec ? 0.0 : static_cast<double>(size / 32);
        e.rays = rays * methods;
        e.rays_key = "/workload/rays_file";
        e.rays_detail = count_text(rays) + " rays x " + count_text(methods) + " method(s)";
        e.memory_bytes += rays * (kBytesPerFileRay + methods * sizeof(RayCounts));  // + each method's per-ray counts
    } else {
        pixels = static_cast<double>(w.width) * w.height;
        const double per_path = 1.0 + (w.type == WorkloadType::Camera ? w.bounces : 0);
        e.rays = pixels * w.spp * per_path * methods;
        // Name the factor furthest above its default (800 x 800, 4 spp, 4 rays per path).
        const std::pair<double, const char*> factors[] = {{w.width / 800.0, "/workload/width"},
                                                          {w.height / 800.0, "/workload/height"},
                                                          {w.spp / 4.0, "/workload/spp"},
                                                          {per_path / 4.0, "/workload/bounces"}};
        e.rays_key = std::max_element(std::begin(factors), std::end(factors), [](const auto& a, const auto& b) {
                         return a.first < b.first;
                     })->second;
        e.rays_detail = std::to_string(w.width) + " x " + std::to_string(w.height) + " pixels x " +
                        std::to_string(w.spp) + " spp x " + count_text(per_path) + " rays per path x " +
                        count_text(methods) + " method(s)";
        // A sampled run traces 1/k of the tiles: 1/k of the rays (and of the
        // recorded rays and hits below); the per-pixel arrays stay full-frame.
        if (const std::uint32_t k = sample_k(c.sampling.fraction); k > 1) {
            e.rays /= k;
            e.rays_detail += " x 1/" + std::to_string(k) + " of the tiles (sampled)";
        }
    }
    const double pixel_bytes = pixels * kBytesPerPixel * methods;
    const double recorded = (c.output.write_rays || c.output.write_hits) ? e.rays * kBytesPerRecordedRay : 0.0;
    std::string prim_key;
    e.primitives = procedural_primitives(c.scene, c.kind, prim_key) *
                   (c.kind == PrimitiveKind::Phantom ? c.subdivision : 1);
    const double prim_bytes = e.primitives * kBytesPerPrimitive;
    e.memory_bytes += pixel_bytes + recorded + prim_bytes;
    if (prim_bytes >= pixel_bytes && prim_bytes >= recorded) {
        e.memory_key = prim_key.empty() ? "/scene" : prim_key;
        e.memory_detail = count_text(e.primitives) + " primitives";
    } else if (pixel_bytes >= recorded) {
        e.memory_key = "/workload/width";
        e.memory_detail = std::to_string(w.width) + " x " + std::to_string(w.height) + " pixels x " +
                          count_text(methods) + " method(s)";
    } else {
        e.memory_key = c.output.write_rays ? "/output/rays" : "/output/hits";
        e.memory_detail = "recording " + count_text(e.rays) + " rays and hits";
    }
    add_method_bytes(c, c.scene.type == SceneType::Hair ? static_cast<double>(c.scene.hair.strands) : 0.0, e);
    add_break_even(c, e);
    return e;
}

WorkEstimate estimate_scene_work(const RunConfig& c, const Scene& scene) {
    WorkEstimate e = estimate_config_work(c);
    const double strands = c.scene.type == SceneType::Hair ? static_cast<double>(c.scene.hair.strands) : 0.0;
    const double before = e.primitives * kBytesPerPrimitive + method_bytes(c, e.primitives, strands).first;
    e.primitives = static_cast<double>(primitive_count(scene.strands, c.kind, c.subdivision)) +
                   static_cast<double>(scene.mesh.triangles.size());
    const double prim_bytes = e.primitives * kBytesPerPrimitive;
    e.memory_bytes += prim_bytes - before;
    if (prim_bytes >= 0.5 * e.memory_bytes) {
        e.memory_key = "/scene";
        e.memory_detail = count_text(e.primitives) + " primitives (" +
                          count_text(static_cast<double>(scene.strands.segment_count())) + " segments, " +
                          count_text(static_cast<double>(scene.mesh.triangles.size())) + " triangles)";
    }
    add_method_bytes(c, static_cast<double>(scene.strands.strand_count()), e);
    return e;
}

WorkEstimate combine_work(const std::vector<WorkEstimate>& points) {
    WorkEstimate total;
    double largest_rays = -1.0, largest_break_even = -1.0;
    for (const WorkEstimate& p : points) {
        total.break_even += p.break_even;
        if (p.break_even > largest_break_even) {
            largest_break_even = p.break_even;
            total.break_even_key = p.break_even_key;
            total.break_even_detail = p.break_even_detail;
        }
        total.rays += p.rays;
        if (p.rays > largest_rays) {
            largest_rays = p.rays;
            total.rays_key = p.rays_key;
            total.rays_detail = p.rays_detail;
        }
        if (p.memory_bytes >= total.memory_bytes) {
            total.memory_bytes = p.memory_bytes;
            total.primitives = p.primitives;
            total.memory_key = p.memory_key;
            total.memory_detail = p.memory_detail;
        }
    }
    if (points.size() > 1) {
        total.rays_detail = count_text(static_cast<double>(points.size())) +
                            " sweep points, the largest " + total.rays_detail;
        if (total.break_even > 0.0)
            total.break_even_detail = count_text(static_cast<double>(points.size())) + " sweep points, the largest " +
                                      total.break_even_detail;
    }
    return total;
}

void check_work(const WorkEstimate& e, const WorkLimits& limits, const std::string& file) {
    if (limits.force) return;
    if (e.rays > limits.max_rays)
        throw InputError(file + ": " + e.rays_key + ": about " + count_text(e.rays) + " rays (" +
                         e.rays_detail + ") exceed --max-rays " + count_text(limits.max_rays) +
                         " (raise it or pass --force to run anyway)");
    const double ceiling = memory_ceiling(limits);
    if (e.memory_bytes > ceiling)
        throw InputError(file + ": " + e.memory_key + ": about " + format_estimate_bytes(e.memory_bytes) +
                         " of memory (" + e.memory_detail + ") exceed --max-memory " +
                         format_estimate_bytes(ceiling) + " (raise it or pass --force to run anyway)");
    if (e.break_even > limits.max_break_even)
        throw InputError(file + ": " + e.break_even_key + ": about " + count_text(e.break_even) +
                         " break-even cell prices (" + e.break_even_detail + ") exceed --max-break-even " +
                         count_text(limits.max_break_even) + " (fewer cells or uncertainty.draws, raise it, or pass "
                         "--force to run anyway)");
}

}  // namespace rtc
