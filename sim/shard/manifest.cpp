#include "sim/shard/manifest.h"

#include "core/input_error.h"
#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"

#include <filesystem>

namespace rtc {

namespace {

constexpr const char* kFormat = "rtcsim-shard-3";  // 2: config_hash, frame identities; 3: inputs

}  // namespace

nlohmann::json manifest_json(const ShardManifest& m) {
    nlohmann::json units = nlohmann::json::array();
    for (const ShardManifest::Unit& u : m.units)
        units.push_back({{"point", u.unit.point}, {"band", u.unit.band}, {"bands", u.unit.bands}, {"frames", u.frames}});
    return {{"format", kFormat},      {"build", m.build},   {"shard", m.spec.index}, {"shards", m.spec.count},
            {"config_file", m.config_file}, {"points", m.points}, {"units", units}, {"sets", m.sets},
            {"config_text", m.config_text}, {"config_hash", m.config_hash}, {"inputs", m.inputs}};
}

ShardManifest read_manifest(const std::string& dir) {
    const std::string file = (std::filesystem::path(dir) / "shard.json").string();
    std::error_code ec;  // a symlink loop or an over-long name: an InputError, not a filesystem_error
    if (!std::filesystem::exists(file, ec))
        throw InputError(file + (ec ? ": cannot access (" + ec.message() + ")"
                                    : ": not found (the shard did not finish, or " + dir + " is not a shard directory)"));
    const nlohmann::json j = parse_json_text(read_text_file(file), file);
    const JsonReader r(j, file);
    r.allow_only({"format", "build", "shard", "shards", "config_file", "points", "units", "sets", "config_text",
                  "config_hash", "inputs"});
    ShardManifest m;
    m.dir = dir;
    const std::string format = r.string("format", std::nullopt);
    if (format != kFormat) r.fail("format", "\"" + format + "\" is not " + kFormat + " (another rtcsim version?)");
    m.build = r.string("build", std::nullopt);
    m.spec.count = static_cast<std::uint32_t>(r.integer("shards", std::nullopt, 1, 100000));
    m.spec.index = static_cast<std::uint32_t>(r.integer("shard", std::nullopt, 0, m.spec.count - 1));
    m.config_file = r.string("config_file", std::nullopt);
    m.points = static_cast<std::size_t>(r.integer("points", std::nullopt, 1, 1000000000));
    m.config_text = r.string("config_text", std::nullopt);
    m.config_hash = r.string("config_hash", std::nullopt);
    if (!j.contains("sets") || !j["sets"].is_array()) r.fail("sets", "expected an array of strings");
    for (std::size_t i = 0; i < j["sets"].size(); ++i) {
        if (!j["sets"][i].is_string()) r.fail("sets/" + std::to_string(i), "expected a string");
        m.sets.push_back(j["sets"][i].get<std::string>());
    }
    const JsonReader inputs = r.child("inputs");
    for (const auto& [path, hash] : inputs.json().items()) m.inputs[path] = inputs.string(path, std::nullopt);
    if (!j.contains("units") || !j["units"].is_array()) r.fail("units", "expected an array");
    const nlohmann::json& units = j["units"];
    for (std::size_t i = 0; i < units.size(); ++i) {
        const JsonReader u(units[i], file, "/units/" + std::to_string(i));
        u.require_object();
        u.allow_only({"point", "band", "bands", "frames"});
        ShardManifest::Unit unit;
        unit.unit.point = static_cast<std::size_t>(
            u.integer("point", std::nullopt, 0, static_cast<long long>(m.points) - 1));
        unit.unit.bands = static_cast<std::uint32_t>(u.integer("bands", std::nullopt, 1, 100000));
        unit.unit.band = static_cast<std::uint32_t>(u.integer("band", std::nullopt, 0, unit.unit.bands - 1));
        const JsonReader frames = u.child("frames");
        for (const auto& [method, path] : frames.json().items()) unit.frames[method] = frames.string(method, std::nullopt);
        m.units.push_back(std::move(unit));
    }
    return m;
}

void check_same_inputs(const std::map<std::string, std::string>& then, const std::string& what,
                       const std::map<std::string, std::string>& now, const std::string& now_what) {
    for (const auto& [path, hash] : now) {
        const auto it = then.find(path);
        if (it == then.end())
            throw InputError(what + ": /inputs: " + path + " is read by " + now_what + " but was not by " + what +
                             " (shards of another plan?)");
        if (it->second != hash)
            throw InputError(path + ": content hash " + hash + " in " + now_what + ", " + it->second + " in " + what +
                             ": the file was edited in between (rerun the shards with one version of it)");
    }
    for (const auto& [path, hash] : then)
        if (!now.count(path))
            throw InputError(what + ": /inputs: " + path + " was read by " + what + " but is not by " + now_what +
                             " (shards of another plan?)");
}

std::vector<ShardManifest> check_shard_set(std::vector<ShardManifest> shards) {
    if (shards.empty()) throw InputError("merge: no shard directories given");
    const ShardManifest& first = shards.front();
    const std::uint32_t n = first.spec.count;
    std::vector<ShardManifest*> by_index(n, nullptr);
    for (ShardManifest& s : shards) {
        const std::string what = s.dir + "/shard.json";
        if (s.build != first.build)
            throw InputError(what + ": /build: written by rtcsim " + s.build + ", " + first.dir + " by " +
                             first.build + " (rerun every shard with one build)");
        if (s.spec.count != n)
            throw InputError(what + ": /shards: " + std::to_string(s.spec.count) + " shards, " + first.dir + " has " +
                             std::to_string(n));
        if (s.points != first.points)
            throw InputError(what + ": /points: " + std::to_string(s.points) + " sweep points, " + first.dir +
                             " has " + std::to_string(first.points) + " (shards of different runs)");
        if (s.config_text != first.config_text || s.sets != first.sets || s.config_file != first.config_file ||
            s.config_hash != first.config_hash)
            throw InputError(what + ": /config_text: not the config (or --set overrides) of " + first.dir +
                             " (shards of different runs)");
        check_same_inputs(first.inputs, first.dir + "/shard.json", s.inputs, what);
        if (by_index[s.spec.index])
            throw InputError(what + ": /shard: shard " + std::to_string(s.spec.index) + " given twice (also " +
                             by_index[s.spec.index]->dir + ")");
        by_index[s.spec.index] = &s;
    }
    std::string missing;
    for (std::uint32_t i = 0; i < n; ++i)
        if (!by_index[i]) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    if (!missing.empty())
        throw InputError("merge: shard(s) " + missing + " of " + std::to_string(n) +
                         " missing: run each with `simulate " + first.config_file + " --shard I/" + std::to_string(n) +
                         " --out DIR` (or scripts/slurm-submit --resume) and merge all " + std::to_string(n));
    std::vector<ShardManifest> ordered;
    for (ShardManifest* s : by_index) ordered.push_back(std::move(*s));
    return ordered;
}

}  // namespace rtc
