#include "sim/config/run_config.h"

#include "sim/util/json_reader.h"
#include "sim/util/paths.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

namespace rtc {

namespace {

BuildOptions read_build(const JsonReader& r, BuildOptions o) {
    o.width = static_cast<int>(r.integer("width", o.width, 2, 8));
    if (o.width != 2 && o.width != 4 && o.width != 8)
        r.fail("width", "expected 2, 4 or 8, got " + std::to_string(o.width));
    o.bins = static_cast<int>(r.integer("bins", o.bins, 2, 64));
    return o;
}

BreakEvenAxis read_axis(const JsonReader& r) {
    r.allow_only({"events", "min", "max", "scale"});
    BreakEvenAxis a;
    a.scale = r.boolean("scale", false);
    const nlohmann::json* ev = r.has("events") ? &r.json()["events"] : nullptr;
    if (!ev || !ev->is_array() || ev->empty()) r.fail("events", "expected a non-empty list of event names");
    for (std::size_t i = 0; i < ev->size(); ++i) {
        const auto e = (*ev)[i].is_string() ? event_from_name((*ev)[i].get<std::string>()) : std::nullopt;
        if (!e) r.fail("events/" + std::to_string(i), "unknown event " + describe((*ev)[i]) + " (see core/events.h)");
        if (std::find(a.events.begin(), a.events.end(), *e) != a.events.end())
            r.fail("events/" + std::to_string(i), std::string(event_name(*e)) + " is listed twice");
        a.events.push_back(*e);
    }
    a.min = r.number("min", std::nullopt, 1e-6, 1e9);
    a.max = r.number("max", std::nullopt, 1e-6, 1e9);
    if (!(a.max > a.min)) r.fail("max", "must be > min");
    return a;
}

// The BVH node width the run's presets build (execution.bvh_width: RDNA4's
// driver builds 8-wide nodes, RDNA2/3's 4-wide). One traced frame serves
// every preset, so presets that name a width must agree, and a config that
// sets bvh.width must set theirs; a run whose presets name none keeps the
// config's width (4 by default: NVIDIA's node width is not public).
void preset_bvh_width(RunConfig& c, bool width_given) {
    const CostModel* named = nullptr;
    std::size_t at = 0;
    for (std::size_t p = 0; p < c.costs.size(); ++p) {
        const CostModel& cost = *c.costs[p];
        if (cost.execution.bvh_width == 0) continue;
        const std::string where = c.file + ": /cost/" + std::to_string(p) + ": " + cost.name + " builds " +
                                  std::to_string(cost.execution.bvh_width) + "-wide nodes (its execution.bvh_width)";
        if (named && named->execution.bvh_width != cost.execution.bvh_width)
            throw InputError(where + ", /cost/" + std::to_string(at) + " (" + named->name + ") " +
                             std::to_string(named->execution.bvh_width) +
                             "-wide ones: one run traces one BVH, so run them in separate configs");
        if (width_given && c.build.tlas.width != cost.execution.bvh_width)
            throw InputError(where + ", but the config sets bvh.width " + std::to_string(c.build.tlas.width) +
                             ": drop bvh.width, or run the preset in another config");
        if (!named) named = &cost, at = p;
    }
    if (!named) return;
    c.build.tlas.width = c.build.custom_blas.width = c.build.triangle_blas.width = named->execution.bvh_width;
}

template <class Model>
std::shared_ptr<const Model> load_once(std::map<std::string, std::shared_ptr<const Model>>& cache,
                                       const std::string& path, Model (*load)(const std::string&)) {
    auto& slot = cache[path];
    if (!slot) slot = std::make_shared<const Model>(load(path));
    return slot;
}

// The presets loaded, and what they must agree on: one traced frame serves
// every preset, so warp presets must group rays alike, and a break-even map
// names one of them and sweeps events it prices.
void load_presets(RunConfig& c, PresetCache& cache) {
    for (std::size_t p = 0; p < c.cost_presets.size(); ++p) {
        try {
            c.costs.push_back(load_once(cache.costs, c.cost_presets[p], &load_cost_model));
        } catch (const InputError& e) {
            // The preset's error names its file and key; say which of the
            // config's entries led there (a derived preset's base is not in the config).
            throw InputError(std::string(e.what()) + " (" + c.file + ": /cost/" + std::to_string(p) + ")");
        }
    }
    c.memory = load_once(cache.memory, c.memory_preset, &load_memory_model);
    // A preset's name keys its results in report.json and names its
    // cycles_<method>_<name>.npy: two presets of one name (a derived preset
    // copied without renaming it) would overwrite each other's.
    for (std::size_t p = 0; p < c.costs.size(); ++p) {
        const std::string& name = c.costs[p]->name;
        const std::string where = c.file + ": /cost/" + std::to_string(p) + ": preset \"" + name + "\" (" +
                                  c.cost_presets[p] + ")";
        if (name.empty() || name.size() > kMaxFileNamePart)
            throw InputError(where + ": a preset's name must be 1 to " + std::to_string(kMaxFileNamePart) +
                             " bytes long (it names output files)");
        // Checked here, where the registry is known (presets live below the
        // methods): a misspelt name would label nothing, with exit 0.
        for (const auto& [method, why] : c.costs[p]->hypothetical)
            if (!find_method(method))
                throw InputError(c.cost_presets[p] + ": /hypothetical/" + method + ": not a method (expected one of " +
                                 method_names_list() + ")");
        for (std::size_t q = 0; q < p; ++q)
            if (file_name_part(c.costs[q]->name) == file_name_part(name))
                throw InputError(where + (c.costs[q]->name == name ? ": has the name of /cost/" : ": names the same files as /cost/") +
                                 std::to_string(q) + " (" + c.cost_presets[q] +
                                 "): presets of one run need distinct names; rename one");
    }
    const CostModel* first_warp = nullptr;
    for (std::size_t p = 0; p < c.costs.size(); ++p) {
        const CostModel& cost = *c.costs[p];
        if (!cost.execution.warp()) continue;
        if (!first_warp) first_warp = &cost;
        if (!first_warp->execution.same_grouping(cost.execution))
            throw InputError(c.file + ": /cost/" + std::to_string(p) + ": " + cost.name +
                             " groups rays into other warps (warp_width, tile) than " + c.costs[0]->name +
                             "; presets of one run must share them");
        // The SM needs the register footprint of this run's pipelines (with
        // and without its intersection program) before anything is traced.
        if (cost.execution.sm.enabled) {
            try {
                for (const bool programs : {true, false})
                    (void)cost.execution.sm.pipeline_registers(pipeline_program(c.kind, c.trace.phantom.program, programs));
            } catch (const std::invalid_argument& e) {
                throw InputError(c.file + ": /cost/" + std::to_string(p) + ": " + cost.name + ": " + e.what());
            }
        }
    }
    std::vector<const CostModel*> costs;
    for (const auto& m : c.costs) costs.push_back(m.get());
    for (const BreakEvenSpec& spec : c.break_even) check_break_even_preset(spec, costs, c.file);
}

}  // namespace

BreakEvenSpec parse_break_even_spec(const nlohmann::json& map, const std::string& file, const std::string& path,
                                    const std::vector<std::string>& methods) {
    const JsonReader b(map, file, path);
    if (!map.is_object()) b.fail("", "expected an object");
    b.allow_only({"name", "preset", "x", "y", "cells", "methods"});
    BreakEvenSpec spec;
    spec.name = b.string("name", std::nullopt);
    spec.preset = b.string("preset", std::nullopt);
    spec.x = read_axis(b.child("x"));
    spec.y = read_axis(b.child("y"));
    // The name is a file name (break_even_<name>.png), checked now, not after tracing.
    const bool bad_name = spec.name.empty() || spec.name.size() > kMaxFileNamePart || spec.name.front() == '.' ||
                          file_name_part(spec.name) != spec.name;
    if (bad_name)
        b.fail("name", "\"" + spec.name + "\" cannot name the map's files break_even_<name>.png: use 1 to " +
                           std::to_string(kMaxFileNamePart) + " letters, digits, '-', '_' or '.', not starting with '.'");
    for (std::size_t k = 0; k < spec.y.events.size(); ++k) {
        const Event e = spec.y.events[k];
        if (std::find(spec.x.events.begin(), spec.x.events.end(), e) != spec.x.events.end())
            b.fail("y/events/" + std::to_string(k), std::string(event_name(e)) + " is on the x axis too: an event has one cost");
    }
    spec.cells = static_cast<int>(b.integer("cells", 48, 2, 512));
    if (const nlohmann::json* ms = b.has("methods") ? &b.json()["methods"] : nullptr) {
        if (!ms->is_array() || ms->size() < 2) b.fail("methods", "expected a list of at least two of the run's methods");
        for (std::size_t k = 0; k < ms->size(); ++k) {
            const std::string key = "methods/" + std::to_string(k);
            if (!(*ms)[k].is_string()) b.fail(key, "expected a method name, got " + describe((*ms)[k]));
            const std::string name = (*ms)[k].get<std::string>();
            if (std::find(methods.begin(), methods.end(), name) == methods.end())
                b.fail(key, "\"" + name + "\" is not one of the run's methods");
            if (std::find(spec.methods.begin(), spec.methods.end(), name) != spec.methods.end())
                b.fail(key, "\"" + name + "\" is listed twice");
            spec.methods.push_back(name);
        }
    }
    return spec;
}

void check_break_even_preset(const BreakEvenSpec& spec, const std::vector<const CostModel*>& costs,
                             const std::string& file) {
    const CostModel* base = nullptr;
    for (const CostModel* m : costs)
        if (m->name == spec.preset) base = m;
    if (!base)
        throw InputError(file + ": /break_even: preset \"" + spec.preset + "\" is not one of the run's cost presets");
    // An axis over an event the preset does not price (a program by name
    // under operation-class pricing) would add its cost on top of the
    // operations that already price that program.
    for (const BreakEvenAxis* axis : {&spec.x, &spec.y})
        for (const Event e : axis->events)
            if (!base->prices(e)) throw InputError(file + ": /break_even: map \"" + spec.name + "\": " + base->unpriced(e));
}

RunConfig parse_run_config(const nlohmann::json& config, const std::string& file, PresetCache* presets) {
    const JsonReader r(config, file);
    r.allow_only({"name", "description", "scene", "primitives", "methods", "baseline", "bvh", "traversal",
                  "cluster", "cost", "memory", "workload", "output", "uncertainty", "calibrate", "break_even", "sampling"});
    RunConfig c;
    c.file = file;
    c.name = r.string("name", std::filesystem::path(file).stem().string());
    c.description = r.string("description", "");
    if (!r.has("scene")) r.fail("scene", "missing (every config names a scene)");
    c.scene = parse_scene(JsonReader(config["scene"], file, "/scene"));

    if (r.has("primitives")) {
        const JsonReader p = r.child("primitives");
        p.allow_only({"kind", "subdivision", "obb"});
        c.kind = *kind_from_name(p.choice("kind", "capsule", {"cylinder", "capsule", "link", "phantom"}));
        c.subdivision = static_cast<int>(p.integer("subdivision", 1, 1, 8));
        if (c.subdivision != 1 && c.subdivision != 2 && c.subdivision != 4 && c.subdivision != 8)
            p.fail("subdivision", "expected 1, 2, 4 or 8, got " + std::to_string(c.subdivision));
        c.build.obb = *obb_variant_from_name(p.choice("obb", "paper", {"paper", "tight"}));
    }
    if (r.has("methods")) {
        const nlohmann::json& m = config["methods"];
        if (!m.is_array() || m.empty())
            r.fail("methods", "expected a non-empty list such as [\"ref\", \"obb\"], got " + describe(m));
        c.methods.clear();
        for (std::size_t i = 0; i < m.size(); ++i) {
            const std::string key = "methods/" + std::to_string(i);
            if (!m[i].is_string() || !find_method(m[i].get<std::string>()))
                r.fail(key, "expected one of " + method_names_list() + ", got " + describe(m[i]));
            const std::string name = m[i].get<std::string>();
            if (std::find(c.methods.begin(), c.methods.end(), name) != c.methods.end())
                r.fail(key, "\"" + name + "\" is listed twice");
            c.methods.push_back(name);
        }
    }
    c.baseline = r.string("baseline", "ref");
    if (r.has("baseline") &&
        std::find(c.methods.begin(), c.methods.end(), c.baseline) == c.methods.end())
        r.fail("baseline", "\"" + c.baseline + "\" is not one of the run's methods");
    // Leaf sizes follow the hardware: one box per custom primitive and per
    // instance; triangles may share leaves.
    c.build.custom_blas.max_leaf_size = 1;
    c.build.tlas.max_leaf_size = 1;
    c.build.triangle_blas.max_leaf_size = 4;
    if (r.has("bvh")) {
        const JsonReader b = r.child("bvh");
        b.allow_only({"width", "bins", "triangle_leaf_size", "oriented_triangles"});
        c.build.custom_blas = read_build(b, c.build.custom_blas);
        c.build.tlas = read_build(b, c.build.tlas);
        c.build.triangle_blas = read_build(b, c.build.triangle_blas);
        c.build.triangle_blas.max_leaf_size =
            static_cast<int>(b.integer("triangle_leaf_size", 4, 1, 16));
        c.build.oriented_triangles = b.boolean("oriented_triangles", false);
    }
    if (r.has("cluster")) {  // read by the cluster method only
        const JsonReader k = r.child("cluster");
        k.allow_only({"strategy", "size", "frame"});
        c.build.cluster.strategy = k.choice("strategy", "orientation", {"strand", "orientation"}) == "strand"
                                       ? ClusterStrategy::Strand
                                       : ClusterStrategy::Orientation;
        c.build.cluster.size = static_cast<int>(k.integer("size", 16, 1, 65536));
        c.build.cluster.frame = k.choice("frame", "best", {"best", "principal"}) == "principal"
                                    ? ClusterFrame::Principal
                                    : ClusterFrame::Best;
    }
    if (r.has("traversal")) {
        const JsonReader t = r.child("traversal");
        t.allow_only({"schedule", "phantom_early_out", "phantom_program"});
        c.trace.schedule = t.choice("schedule", "immediate", {"immediate", "deferred"}) == "deferred"
                               ? IsSchedule::Deferred
                               : IsSchedule::Immediate;
        c.trace.phantom.early_out = t.boolean("phantom_early_out", true);
        c.trace.phantom.program =
            *phantom_program_from_name(t.choice("phantom_program", "bracketed", {"bracketed", "paper"}));
    }
    // Presets by name (searched in the preset directories) or by path
    // (relative to the config file): sim/util/paths.h.
    if (r.has("cost")) {
        const nlohmann::json& cost = config["cost"];
        c.cost_presets.clear();
        if (cost.is_string()) {
            c.cost_presets.push_back(resolve_preset(cost.get<std::string>(), file, "/cost"));
        } else if (cost.is_array() && !cost.empty()) {
            for (std::size_t i = 0; i < cost.size(); ++i) {
                const std::string key = "/cost/" + std::to_string(i);
                if (!cost[i].is_string())
                    r.fail("cost/" + std::to_string(i), "expected a preset name or path, got " + describe(cost[i]));
                c.cost_presets.push_back(resolve_preset(cost[i].get<std::string>(), file, key));
            }
        } else {
            r.fail("cost", "expected a preset name or path, or a list of them, got " + describe(cost));
        }
    } else {
        for (auto& p : c.cost_presets) p = resolve_preset(p, file, "/cost (default)");
    }
    c.memory_preset = resolve_preset(r.string("memory", c.memory_preset), file,
                                     r.has("memory") ? "/memory" : "/memory (default)");
    if (r.has("workload")) c.workload = parse_workload(r.child("workload"));
    if (r.has("output")) {
        const JsonReader o = r.child("output");
        o.allow_only({"images", "arrays", "rays", "hits"});
        c.output.images = o.boolean("images", true);
        c.output.arrays = o.boolean("arrays", true);
        c.output.write_rays = o.boolean("rays", false);
        c.output.write_hits = o.boolean("hits", false);
    }
    if (r.has("uncertainty")) {
        const JsonReader u = r.child("uncertainty");
        u.allow_only({"draws", "seed"});
        c.uncertainty.draws = static_cast<int>(u.integer("draws", 64, 0, 4096));
        c.uncertainty.seed = static_cast<std::uint64_t>(u.integer("seed", 1, 0, 1LL << 53));
    }
    if (r.has("sampling")) {
        const JsonReader sr = r.child("sampling");
        sr.allow_only({"fraction", "seed"});
        c.sampling.fraction = sr.number("fraction", 1.0, 1e-6, 1.0);
        if (!(c.sampling.fraction > 0.0)) sr.fail("fraction", "must be > 0 (1: every tile)");
        c.sampling.seed = static_cast<std::uint64_t>(sr.integer("seed", 1, 0, 1LL << 53));
        if (sample_k(c.sampling.fraction) > 1 && c.workload.type == WorkloadType::Rays)
            sr.fail("fraction", "sampling traces warp tiles of a camera workload; a ray-file workload runs whole "
                                "(fraction 1)");
    }
    if (r.has("break_even")) {
        const nlohmann::json& list = config["break_even"];
        if (!list.is_array()) r.fail("break_even", "expected a list of maps");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string path = "/break_even/" + std::to_string(i);
            BreakEvenSpec spec = parse_break_even_spec(list[i], file, path, c.methods);
            for (std::size_t k = 0; k < c.break_even.size(); ++k)
                if (c.break_even[k].name == spec.name)
                    JsonReader(list[i], file, path).fail("name", "\"" + spec.name + "\" is also the name of /break_even/" +
                                                                  std::to_string(k) + " (each map is written to files of its name)");
            c.break_even.push_back(std::move(spec));
        }
    }
    PresetCache local;
    load_presets(c, presets ? *presets : local);
    preset_bvh_width(c, r.has("bvh") && r.child("bvh").has("width"));
    return c;
}

}  // namespace rtc
