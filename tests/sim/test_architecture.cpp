// The architecture as a test (docs/architecture.md): sim/'s folders include
// only the folders below them, no source file (C++ or Python) grows past ~400
// lines, no folder of sim/ or python/ past ~15 files. The link graph (one
// CMake library per folder) catches back-edges between .cpp files; this
// catches header-only ones too.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

namespace fs = std::filesystem;

namespace {

// Each folder and the folders it may include (directly or through others).
const std::map<std::string, std::set<std::string>> kAllowed = {
    {"util", {}},
    {"hardware", {"util"}},
    {"workload", {"hardware", "util"}},
    {"execution", {"workload", "hardware", "util"}},
    {"methods", {"execution", "workload", "hardware", "util"}},
    {"calibrate", {"hardware", "util"}},
    {"config", {"methods", "execution", "workload", "hardware", "calibrate", "util"}},
    {"run", {"config", "methods", "execution", "workload", "hardware", "calibrate", "util"}},
    {"plot", {"util"}},
    {"shard", {"execution", "workload", "hardware", "util"}},
    {"report", {"run", "plot", "config", "methods", "execution", "workload", "hardware", "calibrate", "util"}},
    {"app", {"shard", "report", "run", "plot", "config", "methods", "execution", "workload", "hardware", "calibrate", "util"}},
    {"bench", {"run", "config", "methods", "execution", "workload", "hardware", "calibrate", "util"}},
};

const fs::path kRoot = RTCSIM_SOURCE_DIR;

bool is_source(const fs::path& p) {
    const std::string e = p.extension().string();
    return e == ".h" || e == ".cpp" || e == ".py";
}

}  // namespace

TEST_CASE("architecture: every sim/ folder includes only the folders below it") {
    std::set<std::string> seen;
    for (const auto& dir : fs::directory_iterator(kRoot / "sim")) {
        if (!dir.is_directory()) continue;
        const std::string folder = dir.path().filename().string();
        CAPTURE(folder);
        REQUIRE_MESSAGE(kAllowed.count(folder), "new sim/ folder: add it to kAllowed and docs/architecture.md");
        seen.insert(folder);
        for (const auto& f : fs::recursive_directory_iterator(dir.path())) {  // sub-folders belong to it
            if (!f.is_regular_file() || !is_source(f.path())) continue;
            std::ifstream in(f.path());
            std::string line;
            int n = 0;
            while (std::getline(in, line)) {
                ++n;
                const std::string tag = "#include \"sim/";
                if (line.rfind(tag, 0) != 0) continue;
                const std::string target = line.substr(tag.size(), line.find('/', tag.size()) - tag.size());
                if (target == folder) continue;
                CAPTURE(f.path().filename().string());
                CAPTURE(n);
                CHECK_MESSAGE(kAllowed.at(folder).count(target), std::string(folder + " must not include sim/" + target));
            }
        }
    }
    CHECK(seen.size() == kAllowed.size());
}

// Sizes are guidance, not budgets (../shared/docs/design.md: split by
// concept, never to meet a count): files over ~400 lines and folders over
// ~15 files are reported, for a reader to judge, and fail nothing.
TEST_CASE("architecture: files over ~400 lines and folders over ~15 files are reported") {
    int reported = 0, sources = 0;
    for (const char* top : {"sim", "core", "intersectors", "scenes", "tests", "python"}) {
        if (!fs::exists(kRoot / top)) continue;
        for (const auto& e : fs::recursive_directory_iterator(kRoot / top)) {
            const std::string rel = fs::relative(e.path(), kRoot).string();
            if (rel.find("__pycache__") != std::string::npos) continue;
            if (e.is_directory() && (std::string(top) == "sim" || std::string(top) == "python")) {
                int files = 0;
                for (const auto& f : fs::directory_iterator(e.path())) files += f.is_regular_file();
                if (files > 16) {
                    MESSAGE(rel << ": " << files << " files (guidance ~15)");
                    ++reported;
                }
            }
            if (!e.is_regular_file() || !is_source(e.path())) continue;
            ++sources;
            std::ifstream in(e.path());
            int lines = 0;
            for (std::string l; std::getline(in, l);) ++lines;
            if (lines > 420) {
                MESSAGE(rel << ": " << lines << " lines (guidance ~400)");
                ++reported;
            }
        }
    }
    MESSAGE(reported << " files or folders over the guidance");
    CHECK(sources > 100);  // the walk found the tree (a wrong root would report nothing)
}

// Calls check(line) on every line of every source file under sim/<folder>,
// with the file and line number captured; returns the number of files.
template <class Check>
int for_each_source_line(const std::string& folder, Check check) {
    int files = 0;
    for (const auto& f : fs::recursive_directory_iterator(kRoot / "sim" / folder)) {
        if (!f.is_regular_file() || !is_source(f.path())) continue;
        ++files;
        std::ifstream in(f.path());
        std::string line;
        int n = 0;
        while (std::getline(in, line)) {
            ++n;
            CAPTURE(f.path().filename().string());
            CAPTURE(n);
            check(line);
        }
    }
    return files;
}

TEST_CASE("architecture: sim/run reads no JSON and no config (it takes the typed plan of sim/config)") {
    // A run is handed a RunConfig: scene description, absolute paths, loaded
    // presets (docs/architecture.md, "The path of a config"). Parsing,
    // resolving and loading belong to sim/config and its planner (plan.h).
    const std::string forbidden[] = {"sim/util/json_reader.h", "sim/util/json_file.h", "sim/util/paths.h"};
    const int files = for_each_source_line("run", [&](const std::string& line) {
        CHECK_MESSAGE(line.find("nlohmann") == std::string::npos, "sim/run must not name nlohmann (JSON)");
        if (line.rfind("#include", 0) != 0) return;
        for (const std::string& what : forbidden)
            CHECK_MESSAGE(line.find(what) == std::string::npos, std::string("sim/run must not include " + what));
    });
    CHECK(files > 0);
}

TEST_CASE("architecture: sim/app reads no config JSON after planning (the plan of sim/config is its input)") {
    // The planner (sim/config/plan.h) parses the config, its points and its
    // calibrate block; sim/app runs, fits and reports from the plan. It
    // writes JSON (report.json, shard.json) but reads no config block:
    // no JSON reader, and none of the block parsers.
    const std::string forbidden[] = {"JsonReader", "parse_run_config(", "parse_calibrate(", "load_cost_model(",
                                     "load_memory_model("};
    const int files = for_each_source_line("app", [&](const std::string& line) {
        CHECK_MESSAGE(line.find("sim/util/json_reader.h") == std::string::npos,
                      "sim/app must not include sim/util/json_reader.h");
        for (const std::string& what : forbidden)
            CHECK_MESSAGE(line.find(what) == std::string::npos, std::string("sim/app must not call " + what));
    });
    CHECK(files > 0);
}

TEST_CASE("architecture: every test file keeps its code in its own namespace (the unity batches)") {
    // tests/CMakeLists.txt compiles the test files in batches of 8; two
    // files' helpers of the same name only stay apart inside
    // `namespace RTCSIM_TEST_FILE`, which the build makes unique per file.
    int files = 0;
    for (const auto& f : fs::recursive_directory_iterator(kRoot / "tests")) {
        const std::string name = f.path().filename().string();
        if (!f.is_regular_file() || name.rfind("test_", 0) != 0 || f.path().extension() != ".cpp") continue;
        ++files;
        std::ifstream in(f.path());
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        CAPTURE(name);
        CHECK(text.find("\nnamespace RTCSIM_TEST_FILE {") != std::string::npos);
        CHECK(text.find("}  // namespace RTCSIM_TEST_FILE") != std::string::npos);
    }
    CHECK(files > 50);
}

}  // namespace RTCSIM_TEST_FILE
