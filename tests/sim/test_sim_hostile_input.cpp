// The hostile configs of issue 18, one test per class, through run_all as
// `simulate` runs them (main turns each InputError into exit code 2): number
// overflow in a config or preset, directories given as files, lengths that
// underflow or overflow a float, and work estimates above the ceilings
// (absurd counts, spp, sweeps). Each message names the file and the key or
// line, and the run fails before any large allocation.
#include "core/input_error.h"
#include "sim/app/cli.h"
#include "sim/hardware/cost_model.h"
#include "sim/util/json_file.h"
#include "sim/workload/ray_file.h"
#include "sim/app/run_all.h"
#include "sim/config/work_estimate.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kTiny = "tests/configs/tiny.json";

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "test_sim_hostile_input";
    fs::create_directories(dir);
    return dir / name;
}

std::string error_of(const std::string& config, std::vector<std::string> sets = {}, WorkLimits limits = {}) {
    CliOptions cli;
    cli.config = config;
    cli.out = scratch("out").string();
    fs::remove_all(*cli.out);  // a fresh output directory per run (a non-empty one is refused)
    cli.quiet = true;
    cli.sets = std::move(sets);
    cli.limits = limits;
    try {
        (void)run_all(cli);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

void check_starts(const std::string& msg, const std::string& prefix, const std::string& part = "") {
    CAPTURE(msg);
    CHECK(msg.rfind(prefix, 0) == 0);
    CHECK(msg.find(part) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
}

}  // namespace

TEST_CASE("hostile config: number overflow in a config or a preset names the file and line") {
    const fs::path config = scratch("overflow.json");
    std::ofstream(config) << "{\"name\": \"x\",\n \"scene\": {\"type\": \"bundle\", \"count\": 1e400}}\n";
    check_starts(error_of(config.string()), config.string() + ": line 2: invalid JSON",
                 "number overflow parsing '1e400'");
    const fs::path preset = scratch("preset.json");
    std::string text = read_text_file("configs/hw/turing-per-ray-guess.json");
    const auto at = text.find("\"value\": ");
    REQUIRE(at != std::string::npos);
    text.insert(at + 9, "1e400, \"was\": ");
    std::ofstream(preset) << text;
    check_starts(error_of(kTiny, {"cost=\"" + preset.string() + "\""}), preset.string() + ": line ",
                 "number overflow");
    // Through --set the number stays text and fails as a value of its key.
    check_starts(error_of(kTiny, {"scene.count=1e400"}), kTiny + ": /scene/count: ");
}

TEST_CASE("hostile config: directories given as a config, preset, ray or hit file") {
    const fs::path dir = scratch("a_directory.json");
    fs::create_directories(dir);
    check_starts(error_of(dir.string()), dir.string() + ": is a directory");
    check_starts(error_of(kTiny, {"memory=\"" + dir.string() + "\""}), dir.string() + ": is a directory");
    check_starts(error_of(kTiny, {"workload={\"type\":\"rays\",\"rays_file\":\"" + dir.string() + "\"}"}),
                 dir.string() + ": is a directory");
    CHECK_THROWS_WITH_AS(static_cast<void>(read_hit_file(dir.string())), doctest::Contains("is a directory"), InputError);
}

TEST_CASE("hostile config: lengths that would underflow or overflow a float name their key") {
    check_starts(error_of(kTiny, {"scene.radius=1e-300"}), kTiny + ": /scene/radius: ", "1e-300");
    check_starts(error_of(kTiny, {"scene.length=1e300",
                                  "workload.camera={\"position\":[0,0,5],\"target\":[0,0,0]}"}),
                 kTiny + ": /scene/length: ");
    check_starts(error_of(kTiny, {"scene={\"type\":\"hair\",\"sphere_center\":[1e39,0,0]}"}),
                 kTiny + ": /scene/sphere_center: ", "too large for a float");
    check_starts(error_of(kTiny, {"scene.tilt_deg=1e-40"}), kTiny + ": /scene/tilt_deg: ", "too small");
    check_starts(error_of(kTiny, {"workload.camera={\"fov_deg\":45,\"from\":[1e-300,1,0]}"}),
                 kTiny + ": /workload/camera/from: ", "too small");
}

TEST_CASE("hostile config: work above the ceilings fails with the key, --force lets it pass") {
    check_starts(error_of(kTiny, {"workload.spp=2147483647"}), kTiny + ": /workload/spp: ", "--max-rays");
    check_starts(error_of(kTiny, {"scene.count=4294967295"}), kTiny + ": /scene/count: ", "--max-memory");
    check_starts(error_of(kTiny, {"scene={\"type\":\"hair\",\"strands\":100000000,\"points_per_strand\":40}"}),
                 kTiny + ": /scene/strands: ", "--max-memory");
    // A sweep of 10^6 points fails before it is expanded.
    nlohmann::json axis = nlohmann::json::array();
    for (int i = 0; i < 1000; ++i) axis.push_back(i);
    const std::string sweep = nlohmann::json{{"scene.seed", axis}, {"workload.seed", axis}}.dump();
    check_starts(error_of(kTiny, {"sweep=" + sweep}), kTiny + ": /sweep/", "10000");
    // Explicit ceilings: a tiny run is 48 x 48 x 2 spp x 2 rays x 2 methods.
    WorkLimits low;
    low.max_rays = 1000;
    check_starts(error_of(kTiny, {}, low), kTiny + ": /workload/", "18432 rays");
    low.force = true;
    CHECK(error_of(kTiny, {"output.images=false"}, low) == "(no error)");
    WorkLimits small_memory;
    small_memory.max_memory = 1024;
    check_starts(error_of(kTiny, {}, small_memory), kTiny + ": ", "--max-memory 1 KiB");
    // A file scene is checked once loaded, before any primitive is built.
    const fs::path curves = scratch("curves.txt");
    {
        std::ofstream out(curves);
        for (int i = 0; i <= 1000; ++i) out << i << " 0 0 0.1\n";
    }
    small_memory.max_memory = 100 * 1024;  // 8 x 8 pixels fit, 1000 segments do not
    check_starts(error_of(kTiny, {"scene={\"type\":\"file\",\"curves\":{\"path\":\"" + curves.string() + "\"}}",
                                  "workload.width=8", "workload.height=8", "output.rays=false", "output.hits=false"},
                          small_memory),
                 kTiny + ": /scene: ", "1000 primitives");
}

TEST_CASE("hostile config: the ceilings on the command line") {
    const CliOptions o = parse_cli({"x.json", "--max-rays", "1e9", "--max-memory", "512M", "--force"});
    CHECK(o.limits.max_rays == 1e9);
    CHECK(o.limits.max_memory == 512.0 * 1024 * 1024);
    CHECK(o.limits.force);
    CHECK(parse_byte_size("8G") == 8.0 * 1024 * 1024 * 1024);
    CHECK(parse_byte_size("2GiB") == 2.0 * 1024 * 1024 * 1024);
    CHECK(parse_byte_size("1000") == 1000.0);
    CHECK_FALSE(parse_byte_size("8X"));
    CHECK_FALSE(parse_byte_size("-1G"));
    CHECK_FALSE(parse_byte_size("lots"));
    CHECK_THROWS_WITH_AS(static_cast<void>(parse_cli({"x.json", "--max-rays", "many"})), doctest::Contains("--max-rays"), InputError);
    CHECK_THROWS_WITH_AS(static_cast<void>(parse_cli({"x.json", "--max-memory", "0"})), doctest::Contains("--max-memory"), InputError);
    CHECK(format_estimate_bytes(1536.0 * 1024 * 1024) == "1.5 GiB");
}

TEST_CASE("hostile config: a --set that is not UTF-8 (found by fuzz_config)") {
    // Its key reached the config and made the echo of it throw nlohmann's type_error 316.
    check_starts(error_of(kTiny, {"\xff=1"}), kTiny + ": --set: ", "UTF-8");
    check_starts(error_of(kTiny, {"name=\xfe\xff"}), kTiny + ": --set: ", "UTF-8");
}

TEST_CASE("hostile config: --set key paths and values of any depth exit 2 naming the argument (issue 56)") {
    // 60,000 key levels or a value nested 65,500 deep overflowed the stack
    // (SIGSEGV) when the config was copied; the 128-level limit covered files.
    std::string key = "description";
    for (int i = 0; i < 60000; ++i) key += ".a";
    check_starts(error_of(kTiny, {key + "=1"}), kTiny + ": --set description.a.a", "deeper than 128 levels");
    CHECK(error_of(kTiny, {key + "=1"}).size() < 200);  // the key is shortened, not echoed whole
    const std::string deep_value = std::string(65500, '[') + std::string(65500, ']');
    check_starts(error_of(kTiny, {"description=" + deep_value}), kTiny + ": --set description: ",
                 "deeper than 128 levels");
    // The limit counts the key's levels and the value's together.
    std::string half = "description";
    for (int i = 0; i < 100; ++i) half += ".a";
    check_starts(error_of(kTiny, {half + "=" + std::string(40, '[') + std::string(40, ']')}),
                 kTiny + ": --set description.a", "deeper than 128 levels");
    // A sweep key is a key path too.
    check_starts(error_of(kTiny, {"sweep={\"" + key + "\": [1]}"}), kTiny + ": /sweep/description.a.a",
                 "deeper than 128 levels");
    // Within the limit it is an ordinary (here unknown) key.
    check_starts(error_of(kTiny, {"description.a.a=1"}), kTiny + ": /description");
}

}  // namespace RTCSIM_TEST_FILE
