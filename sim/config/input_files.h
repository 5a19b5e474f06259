// The files a run reads besides its config, from its typed plan: scene
// curves and meshes, the hair emitter mesh, ray files, and every cost and
// memory preset with a derived preset's bases. What `--force` must not
// delete (sim/app/output_dir.h), and what a shard records the content
// hashes of, so that a merge refuses shards that read different versions of
// a file, or files changed since the shards ran (docs/scale-out.md).
#pragma once

#include "sim/config/run_config.h"

#include <string>
#include <vector>

namespace rtc {

struct InputFile {
    std::string path;                  // absolute
    const std::string* text = nullptr;  // a preset: the text loaded, before tracing (owned by the RunConfig)
};

// Each file once, in the order the points name them. Files a scene file
// includes in turn (a pbrt Include, a glTF's external buffers) are not listed.
[[nodiscard]] std::vector<InputFile> input_files(const std::vector<RunConfig>& points);

// The same paths, after `config_file` itself.
[[nodiscard]] std::vector<std::string> input_paths(const std::vector<RunConfig>& points, const std::string& config_file);

}  // namespace rtc
