#include "sim/app/shard_runs.h"

#include "sim/app/output_dir.h"
#include "sim/app/run_all.h"
#include "sim/config/input_files.h"
#include "sim/plot/plot_svg.h"
#include "sim/shard/frame_file.h"
#include "sim/shard/manifest.h"
#include "sim/shard/shard_plan.h"
#include "sim/util/json_file.h"
#include "sim/util/version.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <iostream>

namespace fs = std::filesystem;

namespace rtc {

namespace {

// What must match between the shards and the merging program: a frame file
// is only meaningful to the build that wrote it.
std::string build_id() {
    return std::string(kVersion) + " " + git_commit() + (git_dirty() ? "+dirty" : "");
}

std::string unit_label(const ShardUnit& u, std::size_t points) {
    std::string s = points > 1 ? "point " + std::to_string(u.point) : std::string("the frame");
    if (u.bands > 1) s += ", band " + std::to_string(u.band) + " of " + std::to_string(u.bands);
    return s;
}

// Every input file of the plan (sim/config/input_files.h) -> FNV-1a of its
// contents: a data file as it is now, a preset as it was loaded.
std::map<std::string, std::string> input_file_hashes(const RunPlan& plan) {
    std::map<std::string, std::string> out;
    for (const InputFile& f : input_files(plan.parsed)) out[f.path] = f.text ? config_hash(*f.text) : file_hash(f.path);
    return out;
}

}  // namespace

int run_shard(const CliOptions& cli) {
    if (cli.calibrate)
        throw InputError("simulate: calibrate cannot be sharded (the fit re-prices every wave in one process): "
                         "shard the sweep without calibrate, or calibrate on one machine");
    const ShardSpec spec = *cli.shard;
    const std::string text = read_text_file(cli.config);
    RunPlan plan = plan_config_text(cli.config, text, cli.sets, cli.limits);
    plan.command_line = cli.command_line;
    const std::string out = cli.out ? *cli.out
                                    : default_output_dir(plan.parsed.front().name, "-shard" + std::to_string(spec.index),
                                                         cli.config);
    OutputDir owned(out, cli.limits.force, input_paths(plan.parsed, plan.file));  // locked until the shard ends
    make_dir((fs::path(out) / "frames").string());
    ShardManifest manifest;
    manifest.build = build_id();
    manifest.spec = spec;
    manifest.config_file = fs::absolute(cli.config).lexically_normal().string();
    manifest.config_text = text;
    manifest.sets = cli.sets;
    manifest.points = plan.points.size();
    manifest.config_hash = config_hash(plan.config.dump());
    manifest.inputs = input_file_hashes(plan);  // before tracing; presets as they were loaded
    const std::vector<ShardUnit> units = units_of_shard(plan.points.size(), spec);
    if (!cli.quiet)
        std::cerr << "shard " << spec.index << "/" << spec.count << " of " << cli.config << ": " << units.size()
                  << " unit(s) -> " << out << "\n";
    for (std::size_t k = 0; k < units.size(); ++k) {
        const ShardUnit& u = units[k];
        if (!cli.quiet) std::cerr << "[" << k + 1 << "/" << units.size() << "] " << unit_label(u, plan.points.size()) << "\n";
        RunContext ctx;
        ctx.threads = cli.threads;
        ctx.quiet = cli.quiet;
        ctx.keep_rays = true;  // recorded rays and hits go into the frame files; the merge writes them
        ctx.band = u.band;
        ctx.bands = u.bands;
        const RunResult r = run_point(plan, u.point, ctx);
        ShardManifest::Unit entry;
        entry.unit = u;
        for (const MethodRun& m : r.methods) {
            if (!m.runnable) continue;
            const std::string file = "frames/" + std::to_string(u.point) + "_" + std::to_string(u.band) + "_" +
                                     m.method + ".bin";
            write_frame_file((fs::path(out) / file).string(), m.frame,
                             frame_identity(plan.points[u.point].config.dump(), m.method, u.point, u.band, u.bands));
            entry.frames[m.method] = file;
        }
        manifest.units.push_back(std::move(entry));
    }
    // Last, and atomically: shard.json marks a finished shard (--resume).
    write_file_atomically((fs::path(out) / "shard.json").string(), manifest_json(manifest).dump(2) + "\n");
    owned.finish();
    if (!cli.quiet) std::cerr << "shard " << spec.index << "/" << spec.count << " done: " << out << "/shard.json\n";
    return 0;
}

int run_merge(const CliOptions& cli) {
    std::vector<ShardManifest> manifests;
    for (const std::string& dir : cli.merge_dirs) {
        require_finished_output(dir);  // a killed or failed shard
        manifests.push_back(read_manifest(dir));
    }
    manifests = check_shard_set(std::move(manifests));
    const ShardManifest& first = manifests.front();
    if (first.build != build_id())
        throw InputError(first.dir + "/shard.json: /build: written by rtcsim " + first.build + ", this is " +
                         build_id() + " (merge with the build that ran the shards)");
    // shard.json's overrides are checked as the command line's are, named by their key there.
    for (std::size_t i = 0; i < first.sets.size(); ++i)
        check_set_depth(first.sets[i], first.dir + "/shard.json: /sets/" + std::to_string(i));
    RunPlan plan = plan_config_text(first.config_file, first.config_text, first.sets, cli.limits);
    plan.command_line = cli.command_line;
    if (plan.points.size() != first.points)
        throw InputError(first.dir + "/shard.json: /points: " + std::to_string(first.points) + " sweep points, the config has " +
                         std::to_string(plan.points.size()));
    // shard.json's config is what the merge plans from: it must be the one
    // the shards ran (each frame file is checked against it again).
    if (first.config_hash != config_hash(plan.config.dump()))
        throw InputError(first.dir + "/shard.json: /config_hash: " + first.config_hash + ", but its config_text plans " +
                         config_hash(plan.config.dump()) + " (edited, or written by another build)");
    // The data and preset files as they are now must be the ones the shards
    // read: the merge re-prices with the presets and reports the scene.
    check_same_inputs(first.inputs, first.dir + "/shard.json", input_file_hashes(plan), "the files as they are now");
    // Per point, its bands in order: (shard, unit).
    using Band = std::pair<const ShardManifest*, const ShardManifest::Unit*>;
    std::vector<std::vector<Band>> bands(plan.points.size());
    for (const ShardManifest& m : manifests)
        for (const ShardManifest::Unit& u : m.units) {
            if (u.unit.point >= bands.size())
                throw InputError(m.dir + "/shard.json: /units: point " + std::to_string(u.unit.point) +
                                 " is past the config's " + std::to_string(bands.size()) + " sweep points");
            std::vector<Band>& list = bands[u.unit.point];
            if (list.empty()) list.resize(u.unit.bands);
            if (list.size() != u.unit.bands || list[u.unit.band].first)
                throw InputError(m.dir + "/shard.json: /units: point " + std::to_string(u.unit.point) + " band " +
                                 std::to_string(u.unit.band) + " of " + std::to_string(u.unit.bands) +
                                 " clashes with another shard's");
            list[u.unit.band] = {&m, &u};
        }
    for (std::size_t p = 0; p < bands.size(); ++p)
        for (std::size_t b = 0; b < std::max<std::size_t>(bands[p].size(), 1); ++b)
            if (bands[p].empty() || !bands[p][b].first)
                throw InputError("merge: point " + std::to_string(p) + " band " + std::to_string(b) +
                                 " is in no shard (shards of another plan?)");
    const PointFrames frames = [&](std::size_t point, const std::string& method) {
        const std::vector<Band>& list = bands.at(point);
        const std::string what = "merge: point " + std::to_string(point) + ", method " + method;
        return merge_frame_bands(list.size(), [&](std::size_t b) {
            const auto& [m, u] = list[b];
            const auto it = u->frames.find(method);
            if (it == u->frames.end())
                throw InputError(m->dir + "/shard.json: /units: point " + std::to_string(point) + " band " +
                                 std::to_string(b) + " has no frame of method " + method);
            const std::string file = (fs::path(m->dir) / it->second).string();
            // The frame the config makes, checked before the merge allocates it.
            const WorkloadDesc& w = plan.parsed[point].workload;
            const FrameShape shape = w.type == WorkloadType::Rays ? FrameShape{} : FrameShape{w.width, w.height};
            return read_frame_file(file,
                                   frame_identity(plan.points[point].config.dump(), method, point,
                                                  static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(list.size())),
                                   shape);
        }, what);
    };
    const std::string out = cli.out ? *cli.out : default_output_dir(plan.parsed.front().name, "", first.config_file);
    // Before anything is emptied: --out must not be, hold or lie in a shard
    // directory the merge reads (--force would empty it first).
    for (const ShardManifest& m : manifests) {
        const auto resolved = [](const std::string& p) {
            std::error_code ec;
            const fs::path absolute = fs::absolute(p, ec).lexically_normal();
            const fs::path canonical = fs::weakly_canonical(absolute, ec);
            return ec || canonical.empty() ? absolute : canonical;
        };
        const fs::path target = resolved(out), input = resolved(m.dir);
        const auto [t, i] = std::mismatch(target.begin(), target.end(), input.begin(), input.end());
        if (t == target.end() || i == input.end())
            throw InputError("simulate merge: --out " + out + ": " +
                             (t == target.end() && i == input.end() ? "is the shard directory "
                              : t == target.end()                   ? "holds the shard directory "
                                                                    : "is inside the shard directory ") +
                             m.dir + " it merges: choose another --out");
    }
    OutputDir owned(out, cli.limits.force, input_paths(plan.parsed, plan.file));  // locked until the merge ends
    if (!cli.quiet) std::cerr << "merging " << manifests.size() << " shards -> " << out << "\n";
    const int status = run_planned(plan, cli, out, &frames);
    owned.finish();
    return status;
}

int print_shard_estimates(const CliOptions& cli) {
    WorkLimits limits = cli.limits;
    limits.force = true;  // an estimate of a run above the ceilings is what one wants to see
    const RunPlan plan = plan_config_text(cli.config, read_text_file(cli.config), cli.sets, limits);
    for (std::uint32_t i = 0; i < cli.estimate_shards; ++i) {
        double rays = 0.0, memory = 0.0, primitives = 0.0;
        nlohmann::json points = nlohmann::json::array();
        for (const ShardUnit& u : units_of_shard(plan.points.size(), {i, cli.estimate_shards})) {
            const WorkEstimate w = estimate_config_work(plan.parsed[u.point]);
            rays += w.rays / u.bands;
            memory = std::max(memory, w.memory_bytes);  // points run one after another
            primitives = std::max(primitives, w.primitives);
            points.push_back({{"point", u.point}, {"band", u.band}, {"bands", u.bands}});
        }
        std::cout << nlohmann::json{{"shard", i}, {"shards", cli.estimate_shards}, {"rays", rays},
                                    {"primitives", primitives}, {"memory_bytes", memory}, {"units", points}}.dump()
                  << "\n";
    }
    return 0;
}

}  // namespace rtc
