// libFuzzer harness: what `simulate merge` reads (sim/app/shard_runs.cpp).
// Input starting with '{' is a shard.json: read from a scratch directory,
// checked as a one-shard set, its --set overrides' depth checked, its
// config_text planned with them (small ceilings) against its points and
// config_hash, and its `inputs` (file -> content hash) against the files as
// they are now, as the merge does before reading frames (issue 56: edited
// inputs; the seeds name real presets with right and wrong hashes). Anything else is a frame file after one
// line giving the frame shape and the identity the merge expects (so the
// fuzzer can get past those checks; the seeds carry what their file
// records), read and merged as a one-band frame.
#include "fuzz_common.h"
#include "sim/app/run_all.h"
#include "sim/config/input_files.h"
#include "sim/config/sweep.h"
#include "sim/shard/frame_file.h"
#include "sim/shard/manifest.h"

#include <unistd.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

namespace {

void merge_manifest(const std::uint8_t* data, std::size_t size) {
    // read_manifest takes a directory: the scratch file is its shard.json
    // (the directory is made once and removed at exit).
    static const std::string dir = [] {
        const std::string d = rtc::fuzz::scratch_dir() + "/rtcsim_fuzz_" + std::to_string(getpid()) + "_merge";
        std::filesystem::create_directories(d);
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(rtc::fuzz::scratch_dir() + "/rtcsim_fuzz_" + std::to_string(getpid()) + "_merge", ec);
        });
        return d;
    }();
    std::FILE* f = std::fopen((dir + "/shard.json").c_str(), "wb");
    if (!f) std::abort();
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    std::vector<rtc::ShardManifest> set = rtc::check_shard_set({rtc::read_manifest(dir)});
    const rtc::ShardManifest& m = set.front();
    rtc::WorkLimits limits;
    limits.max_rays = 1e6;
    limits.max_memory = 16.0 * 1024 * 1024;
    limits.max_sweep_points = 16;
    for (std::size_t i = 0; i < m.sets.size(); ++i) rtc::check_set_depth(m.sets[i], "shard.json: /sets");
    const rtc::RunPlan plan = rtc::plan_config_text(m.config_file, m.config_text, m.sets, limits);
    (void)(plan.points.size() == m.points && m.config_hash == rtc::config_hash(plan.config.dump()));
    std::map<std::string, std::string> now;
    for (const rtc::InputFile& f : rtc::input_files(plan.parsed))
        now[f.path] = f.text ? rtc::config_hash(*f.text) : rtc::file_hash(f.path);
    rtc::check_same_inputs(m.inputs, "shard.json", now, "the files as they are now");
}

void merge_frame(const std::uint8_t* data, std::size_t size) {
    // "<width> <height> <identity>": the frame the config makes (0 0: a ray
    // list), at most what a config within the small ceilings above could ask
    // for, and the identity the merge expects.
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::size_t eol = text.find('\n');
    if (eol == std::string::npos) return;
    std::istringstream line(text.substr(0, eol));
    rtc::FrameShape shape;
    if (!(line >> shape.width >> shape.height) || shape.width < 0 || shape.height < 0 ||
        static_cast<double>(shape.width) * shape.height > 1e6)
        return;
    line.get();  // the space before the identity
    std::string identity;
    std::getline(line, identity);
    const std::string path = rtc::fuzz::write_scratch(data + eol + 1, size - eol - 1, ".frame");
    const rtc::FrameResult f = rtc::merge_frame_bands(
        1, [&](std::size_t) { return rtc::read_frame_file(path, identity, shape); }, "fuzz merge");
    (void)f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        if (size > 0 && data[0] == '{')
            merge_manifest(data, size);
        else
            merge_frame(data, size);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
