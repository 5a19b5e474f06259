// Issue 56's output-directory findings: --force never deletes the run's own
// inputs, the mark is never written through a symbolic link, the lock can be
// turned off where a file system has none, and a stop requested while the
// outputs are written keeps the directory from being marked complete.
#include "core/input_error.h"
#include "sim/app/output_dir.h"
#include "sim/app/simulate_main.h"
#include "sim/execution/interrupt.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

fs::path fresh(const std::string& name) {
    const fs::path p = fs::path(RTCSIM_BINARY_DIR) / "test_output_dir_rules" / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

const std::vector<std::string> kSmall = {"--quiet", "--threads", "1", "--set", "workload.width=8",
                                         "--set", "workload.height=8", "--set", "output.images=false"};

int simulate(std::vector<std::string> args) {
    args.insert(args.end(), kSmall.begin(), kSmall.end());
    return simulate_main(args);
}

std::string mark_text(const fs::path& dir) { return read_text_file((dir / kOutputMark).string()); }

}  // namespace

TEST_CASE("output dir: --force refuses to empty a directory holding the run's config, ray file or preset") {
    const fs::path dir = fresh("force_inputs");
    const fs::path out = dir / "out";
    // A finished run that recorded its rays, then a config inside it that replays them.
    REQUIRE(simulate({"tests/configs/tiny.json", "--out", out.string(), "--set", "output.rays=true"}) == 0);
    REQUIRE(fs::exists(out / "rays.bin"));
    std::ofstream(out / "replay.json") << R"({"scene": {"type": "bundle", "count": 60, "radius": 0.01, "tilt_deg": 30, "seed": 2},
        "cost": [")" RTCSIM_SOURCE_DIR R"(/configs/hw/turing-per-ray-guess.json"],
        "workload": {"type": "rays", "rays_file": "rays.bin"}, "output": {"images": false}})";
    // Was: rays.bin deleted by the emptying, then the run failed (or, for a
    // config kept there, the config deleted and exit 0).
    CHECK(simulate_main({(out / "replay.json").string(), "--out", out.string(), "--force", "--quiet"}) == 2);
    CHECK(fs::exists(out / "rays.bin"));
    CHECK(fs::exists(out / "replay.json"));
    // A preset inside it, named from a config outside.
    fs::copy_file(RTCSIM_SOURCE_DIR "/configs/hw/turing-per-ray-guess.json", out / "p.json");
    CHECK(simulate({"tests/configs/tiny.json", "--out", out.string(), "--force", "--set",
                    "cost=[\"" + (out / "p.json").string() + "\"]"}) == 2);
    CHECK(fs::exists(out / "p.json"));
    try {
        OutputDir o(out.string(), true, {(out / "rays.bin").string()});
        FAIL("not refused");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) == out.string() + ": --force would empty it, and it holds " +
                                           (out / "rays.bin").string() +
                                           ", an input of this run: move the input out, or choose another --out");
    }
    // Inputs elsewhere: emptied as before.
    CHECK(simulate({"tests/configs/tiny.json", "--out", out.string(), "--force"}) == 0);
    CHECK_FALSE(fs::exists(out / "replay.json"));
    CHECK_FALSE(fs::exists(out / "p.json"));
}

TEST_CASE("output dir: a mark that is a symbolic link is refused, the original left as it was") {
    const fs::path dir = fresh("symlink");
    const fs::path original = dir / "original", copy = dir / "copy";
    REQUIRE(simulate({"tests/configs/tiny.json", "--out", original.string()}) == 0);
    const std::string before = mark_text(original);
    REQUIRE(before.find("state: complete") != std::string::npos);
    // What `cp -rs` makes: the same tree of symbolic links.
    fs::create_directories(copy);
    for (const auto& entry : fs::directory_iterator(original))
        fs::create_symlink(entry.path(), copy / entry.path().filename());
    for (const bool force : {false, true}) {
        try {
            OutputDir o(copy.string(), force);
            FAIL("not refused");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).rfind((copy / kOutputMark).string() + ": is a symbolic link", 0) == 0);
        }
    }
    CHECK(simulate({"tests/configs/tiny.json", "--out", copy.string(), "--force"}) == 2);
    CHECK(mark_text(original) == before);  // was: "state: running" for good
}

TEST_CASE("output dir: RTCSIM_NO_LOCK=1 runs without the lock") {
    const fs::path dir = fresh("no_lock");
    {
        OutputDir held(dir.string(), false);
        CHECK_THROWS_WITH_AS(OutputDir(dir.string(), false), doctest::Contains("in use by another simulate run"),
                             InputError);
        ::setenv("RTCSIM_NO_LOCK", "1", 1);
        CHECK_NOTHROW(OutputDir(dir.string(), false));  // what a file system without locks needs
        ::unsetenv("RTCSIM_NO_LOCK");
    }
}

TEST_CASE("output dir: a stop requested while the outputs are written is not marked complete") {
    const fs::path dir = fresh("late_stop");
    OutputDir o(dir.string(), false);
    request_interrupt(kSigTerm);
    CHECK_THROWS_AS(o.finish(), Interrupted);
    CHECK(interrupted_exit_code() == 143);
    clear_interrupt();
    CHECK(mark_text(dir).find("state: running") != std::string::npos);
    o.finish();
    CHECK(mark_text(dir).find("state: complete") != std::string::npos);
}

}  // namespace RTCSIM_TEST_FILE
