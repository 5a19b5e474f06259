#include "sim/app/provenance.h"

#include "sim/config/config_json.h"
#include "sim/util/json_file.h"
#include "sim/util/paths.h"
#include "sim/util/process_memory.h"
#include "sim/util/version.h"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <thread>

namespace rtc {

namespace {

using ojson = nlohmann::ordered_json;

// A preset as it was read when the run was planned (before tracing): its
// file and parsed contents, and for a derived preset its bases the same way.
// Not read again here: an edit made while the run traced is not what it used.
ojson preset_json(const std::string& path, const PresetFiles& files) {
    ojson j;
    if (!files || files->empty()) {  // a preset given as text (tests), no file behind it
        j["file"] = path;
        j["contents"] = nullptr;
        return j;
    }
    const auto file_json = [](const PresetFile& f) {
        ojson p;
        p["file"] = f.path;
        p["contents"] = ojson::parse(f.text, nullptr, false);  // parsed when loaded: valid
        return p;
    };
    j = file_json(files->front());
    if (files->size() > 1) {
        ojson bases = ojson::array();
        for (std::size_t i = 1; i < files->size(); ++i) bases.push_back(file_json((*files)[i]));
        j["bases"] = std::move(bases);  // derived_from, then its own base, ...
    }
    return j;
}

}  // namespace

std::string utc_now_iso8601() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

ojson provenance_json(const RunResult& run, unsigned threads, const std::vector<std::string>& command_line) {
    ojson j;
    j["rtcsim_version"] = kVersion;
    j["git_commit"] = git_commit();
    j["git_dirty"] = git_dirty();
    j["date"] = utc_now_iso8601();
    j["threads"] = {{"requested", threads},
                    {"used", threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency())}};
    if (!command_line.empty()) j["command_line"] = command_line;
    j["huge_pages"] = huge_pages_summary();  // RTCSIM_HUGE_PAGES and, under auto, the probe's choice
    j["config_file"] = run.config.file;
    j["data_root"] = data_root().string();  // what "data:..." paths of the config meant
    j["repriced"] = run.repriced;  // priced from the previous sweep point's trace
    j["effective_config"] = run_config_to_json(run.config, run.point.config);
    ojson cost = ojson::array();
    for (std::size_t i = 0; i < run.config.cost_presets.size(); ++i) {
        ojson p = preset_json(run.config.cost_presets[i],
                              i < run.config.costs.size() && run.config.costs[i] ? run.config.costs[i]->files : nullptr);
        p["name"] = i < run.costs.size() ? run.costs[i].name : std::string();
        // The costs it priced with, flattened (a derived preset's deltas
        // applied to its bases, sums of other costs summed), as loaded
        // before tracing: what its contents and bases above came to.
        if (i < run.config.costs.size() && run.config.costs[i])
            p["effective"] = ojson::parse(cost_model_to_json(*run.config.costs[i]));
        cost.push_back(std::move(p));
    }
    j["presets"] = {{"cost", cost}, {"memory", preset_json(run.config.memory_preset,
                                                                       run.config.memory ? run.config.memory->files : nullptr)}};
    return j;
}

}  // namespace rtc
