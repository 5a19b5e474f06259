// Every example command line in `simulate --help` runs (from the source
// tree, as the help says), made small with overrides appended after it.
#include "sim/app/cli.h"
#include "sim/app/simulate_main.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

// The lines of the "examples" section that start with "simulate ".
std::vector<std::vector<std::string>> help_examples() {
    std::vector<std::vector<std::string>> out;
    std::istringstream help(cli_help());
    bool in_examples = false;
    for (std::string line; std::getline(help, line);) {
        if (line.rfind("examples", 0) == 0) {
            in_examples = true;
            continue;
        }
        if (!in_examples) continue;
        if (line.empty()) break;
        std::istringstream words(line);
        std::vector<std::string> args;
        for (std::string w; words >> w;) args.push_back(w);
        if (!args.empty() && args.front() == "simulate") out.push_back({args.begin() + 1, args.end()});
    }
    return out;
}

}  // namespace

TEST_CASE("cli: every example in --help runs") {
    const auto examples = help_examples();
    REQUIRE(examples.size() >= 3);
    std::map<std::string, fs::path> outs;  // an example's --out -> ours (merge examples name them)
    for (std::size_t i = 0; i < examples.size(); ++i) {
        const fs::path out = fs::path(RTCSIM_BINARY_DIR) / "help_examples" / std::to_string(i);
        const bool merge = !examples[i].empty() && examples[i].front() == "merge";
        const bool shard = std::find(examples[i].begin(), examples[i].end(), "--shard") != examples[i].end();
        std::vector<std::string> args;
        for (std::size_t k = 0; k < examples[i].size(); ++k) {  // our own --out instead
            if (examples[i][k] == "--out" && k + 1 < examples[i].size()) {
                outs[examples[i][++k]] = out;
                continue;
            }
            if (examples[i][k].rfind("--out=", 0) == 0) {
                outs[examples[i][k].substr(6)] = out;
                continue;
            }
            const auto earlier = outs.find(examples[i][k]);
            args.push_back(merge && earlier != outs.end() ? earlier->second.string() : examples[i][k]);
        }
        fs::remove_all(out);
        if (!merge)
            for (const char* s : {"workload.width=16", "workload.height=16", "workload.spp=1", "output.images=false"})
                args.insert(args.end(), {"--set", s});
        args.insert(args.end(), {"--quiet", "--threads", "2", "--out", out.string()});
        std::string line = "simulate";
        for (const std::string& a : args) line += " " + a;
        INFO(line);
        CHECK(simulate_main(args) == 0);
        CHECK(fs::exists(out / (shard ? "shard.json" : "summary.csv")));
    }
}

}  // namespace RTCSIM_TEST_FILE
