// shard.json: what a shard ran and where its frames are, written last so
// that its presence means the shard finished (slurm-submit --resume relies on
// it). The merge checks every manifest against the first: same rtcsim build,
// same config (after --set), same shard count and sweep points, and every
// shard present once; then each one's config_hash against the run it plans.
#pragma once

#include "sim/shard/shard_plan.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace rtc {

struct ShardManifest {
    std::string build;            // version and commit of the rtcsim that wrote it
    ShardSpec spec;
    std::string config_file;      // absolute path of the config (relative paths in it resolve from there)
    std::string config_text;      // the config as read (the merge plans the run from it, not from the file)
    std::vector<std::string> sets;  // --set overrides, in order
    std::size_t points = 0;       // sweep points of the whole run
    std::string config_hash;      // config_hash() of the effective config (the merge plans the same, or refuses)
    std::map<std::string, std::string> inputs;  // every data and preset file read -> content hash (sim/config/input_files.h)
    struct Unit {
        ShardUnit unit;
        std::map<std::string, std::string> frames;  // method -> frame file, relative to the shard directory
    };
    std::vector<Unit> units;
    std::string dir;              // where it was read from (not written)
};

[[nodiscard]] nlohmann::json manifest_json(const ShardManifest& m);
// Reads DIR/shard.json; errors name the file and key.
[[nodiscard]] ShardManifest read_manifest(const std::string& dir);

// Throws InputError naming the first input file whose hash differs between `then`
// (what `what` recorded) and `now`, or that only one of them has.
void check_same_inputs(const std::map<std::string, std::string>& then, const std::string& what,
                       const std::map<std::string, std::string>& now, const std::string& now_what);

// Checks that `shards` are the N shards of one run (any order) and returns
// them ordered by index; throws InputError listing what is missing, repeated
// or mixed (other configs, other versions of an input file), with the command that reruns a missing shard.
[[nodiscard]] std::vector<ShardManifest> check_shard_set(std::vector<ShardManifest> shards);

}  // namespace rtc
