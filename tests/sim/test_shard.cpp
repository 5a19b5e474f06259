// Sharded runs (docs/scale-out.md) without a scheduler: the plan covers every
// unit once, and N shards merged give byte-identical outputs to one run
// (report.json equal once provenance and timings are dropped) for a camera
// frame cut into bands under per-ray and warp presets, a sweep, and a ray
// file; a missing, repeated, foreign or damaged shard fails with its name.
#include "core/input_error.h"
#include "sim/app/cli.h"
#include "sim/app/shard_runs.h"
#include "sim/app/simulate_main.h"
#include "sim/shard/frame_file.h"
#include "sim/shard/shard_plan.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kTiny = "tests/configs/tiny.json";

fs::path fresh(const std::string& name) {
    const fs::path p = fs::path(RTCSIM_BINARY_DIR) / "shard_test" / name;
    fs::remove_all(p);
    return p;
}

int simulate(std::vector<std::string> args) {
    args.insert(args.end(), {"--quiet", "--threads", "2"});
    return simulate_main(args);
}

std::string slurp(const fs::path& p) { return read_text_file(p.string()); }

// report.json without what differs between identical runs.
nlohmann::json comparable(nlohmann::json j) {
    if (j.is_object()) {
        for (const char* k : {"provenance", "wall_seconds", "simulator"}) j.erase(k);
        for (auto& [k, v] : j.items()) v = comparable(v);
    } else if (j.is_array()) {
        for (auto& v : j) v = comparable(v);
    }
    return j;
}

// Every file of `a` is in `b` with the same bytes (report.json: comparable()).
void check_same_outputs(const fs::path& a, const fs::path& b) {
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(a)) {
        if (!e.is_regular_file()) continue;
        const fs::path rel = fs::relative(e.path(), a);
        CAPTURE(rel.string());
        REQUIRE(fs::exists(b / rel));
        ++files;
        if (rel.filename() == "report.json")
            CHECK(comparable(nlohmann::json::parse(slurp(e.path()))) ==
                  comparable(nlohmann::json::parse(slurp(b / rel))));
        else
            CHECK(slurp(e.path()) == slurp(b / rel));
    }
    CHECK(files >= 5);
}

// Runs `config` once and as `n` shards (given to the merge in reverse order),
// and checks the merged outputs against the single run's.
void check_sharded_equals_single(const std::string& name, const std::vector<std::string>& config_and_sets,
                                 std::uint32_t n) {
    const fs::path single = fresh(name + "_single");
    std::vector<std::string> args = config_and_sets;
    args.insert(args.end(), {"--out", single.string()});
    REQUIRE(simulate(args) == 0);
    std::vector<std::string> merge = {"merge"};
    for (std::uint32_t i = n; i-- > 0;) {
        const fs::path shard = fresh(name + "_shard" + std::to_string(i));
        std::vector<std::string> a = config_and_sets;
        a.insert(a.end(), {"--shard", std::to_string(i) + "/" + std::to_string(n), "--out", shard.string()});
        REQUIRE(simulate(a) == 0);
        REQUIRE(fs::exists(shard / "shard.json"));
        merge.push_back(shard.string());
    }
    const fs::path merged = fresh(name + "_merged");
    merge.insert(merge.end(), {"--out", merged.string()});
    REQUIRE(simulate(merge) == 0);
    check_same_outputs(single, merged);
}

}  // namespace

TEST_CASE("shard plan: every point and band runs in exactly one shard") {
    for (const std::size_t points : {1u, 3u, 4u, 7u, 16u})
        for (const std::uint32_t shards : {1u, 2u, 4u, 5u, 9u}) {
            CAPTURE(points);
            CAPTURE(shards);
            std::map<std::size_t, std::set<std::uint32_t>> bands;
            std::map<std::size_t, std::uint32_t> band_count;
            std::size_t units = 0;
            for (std::uint32_t i = 0; i < shards; ++i)
                for (const ShardUnit& u : units_of_shard(points, {i, shards})) {
                    ++units;
                    CHECK(bands[u.point].insert(u.band).second);
                    if (band_count.count(u.point)) CHECK(band_count[u.point] == u.bands);
                    band_count[u.point] = u.bands;
                }
            CHECK(bands.size() == points);
            for (const auto& [p, b] : bands) CHECK(b.size() == band_count[p]);
            CHECK(units == std::max<std::size_t>(points, shards));
        }
    // units_of_shard (computed directly, not by listing every unit) is unit
    // index, index + N, ... of shard_units.
    for (const std::size_t points : {1u, 2u, 3u, 5u, 8u, 13u})
        for (const std::uint32_t shards : {1u, 2u, 3u, 7u, 8u, 20u, 31u}) {
            const std::vector<ShardUnit> all = shard_units(points, shards);
            for (std::uint32_t i = 0; i < shards; ++i) {
                CAPTURE(points);
                CAPTURE(shards);
                CAPTURE(i);
                const std::vector<ShardUnit> mine = units_of_shard(points, {i, shards});
                std::size_t k = 0;
                for (std::size_t u = i; u < all.size(); u += shards, ++k) {
                    REQUIRE(k < mine.size());
                    CHECK((mine[k].point == all[u].point && mine[k].band == all[u].band &&
                           mine[k].bands == all[u].bands));
                }
                CHECK(k == mine.size());
            }
        }
    // Bands of tasks tile the frame, also with more bands than tasks.
    for (const std::size_t tasks : {0u, 1u, 5u, 12u, 800u})
        for (const std::uint32_t n : {1u, 3u, 7u}) {
            std::size_t next = 0;
            for (std::uint32_t b = 0; b < n; ++b) {
                const auto [first, last] = band_range(tasks, b, n);
                CHECK(first == next);
                CHECK(last >= first);
                next = last;
            }
            CHECK(next == tasks);
        }
    CHECK_THROWS_AS((void)parse_shard_spec("4/4", "--shard"), InputError);
    CHECK_THROWS_AS((void)parse_shard_spec("1/0", "--shard"), InputError);
    CHECK_THROWS_AS((void)parse_shard_spec("x", "--shard"), InputError);
    CHECK(parse_shard_spec("3/4", "--shard").index == 3);
}

TEST_CASE("shard merge: a frame cut into bands merges into the single run, per-ray and warp presets") {
    check_sharded_equals_single("frame", {kTiny, "--set", "output.rays=false", "--set",
                                          "cost=[\"turing-calibrated\",\"turing-per-ray-guess\",\"turing-per-ray-calibrated\"]"},
                                4);
}

TEST_CASE("shard merge: a sweep over fewer and more shards than points") {
    const std::vector<std::string> sweep = {kTiny, "--set", "output.rays=false", "--set", "output.hits=false",
                                            "--set", "sweep={\"scene.tilt_deg\":[0,45],\"scene.count\":[5,30]}",
                                            "--set", "cost=[\"turing-calibrated\"]"};
    check_sharded_equals_single("sweep3", sweep, 3);  // 4 points over 3 shards
    check_sharded_equals_single("sweep6", sweep, 6);  // 4 points, 2 of them in two bands
}

TEST_CASE("shard merge: a ray file cut into bands replays to the same hits") {
    const fs::path record = fresh("record");
    REQUIRE(simulate({kTiny, "--set", "output.images=false", "--out", record.string()}) == 0);
    check_sharded_equals_single(
        "rays", {kTiny, "--set", "workload={\"type\":\"rays\",\"rays_file\":\"" + (record / "rays.bin").string() + "\"}",
                 "--set", "output.images=false", "--set", "output.rays=false"},
        3);
}

TEST_CASE("shard merge: missing, repeated, foreign and damaged shards fail naming what is wrong") {
    const fs::path s0 = fresh("bad_s0"), s1 = fresh("bad_s1"), other = fresh("bad_other");
    const std::vector<std::string> base = {kTiny, "--set", "output.images=false", "--set", "output.rays=false"};
    auto shard = [&](const fs::path& out, const std::string& spec, std::vector<std::string> extra = {}) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        a.insert(a.end(), {"--shard", spec, "--out", out.string()});
        return simulate(a);
    };
    REQUIRE(shard(s0, "0/2") == 0);
    REQUIRE(shard(s1, "1/2") == 0);
    REQUIRE(shard(other, "1/2", {"--set", "workload.spp=1"}) == 0);
    const auto merge_error = [&](std::vector<std::string> dirs) {
        std::vector<std::string> a = {"merge"};
        a.insert(a.end(), dirs.begin(), dirs.end());
        a.insert(a.end(), {"--out", fresh("bad_merged").string(), "--quiet"});
        try {
            (void)run_merge(parse_cli(a));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    const auto has = [](const std::string& message, const std::string& part) {
        INFO(message);
        CHECK(message.find(part) != std::string::npos);
    };
    has(merge_error({s0.string()}), "shard(s) 1 of 2 missing");
    has(merge_error({s0.string(), s0.string()}), "given twice");
    has(merge_error({s0.string(), other.string()}), "shards of different runs");
    has(merge_error({fresh("empty").string()}), "shard.json: not found");
    // A truncated frame file names the file and byte offset.
    fs::path frame;
    for (const auto& e : fs::directory_iterator(s1 / "frames")) frame = e.path();
    REQUIRE(!frame.empty());
    const std::string bytes = slurp(frame);
    // The identity (after magic, format and event count: a length and text).
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 16, 4);
    REQUIRE(length < 200);
    const std::string identity = bytes.substr(20, length);
    CHECK(identity.find(", band 1 of 2") != std::string::npos);
    std::ofstream(frame, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
    try {
        (void)read_frame_file(frame.string(), identity, {48, 48});
        FAIL("a truncated frame file was read");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find(frame.string() + ": byte ") == 0);
    }
    has(merge_error({s0.string(), s1.string()}), frame.string() + ": byte ");
    // Hostile header fields (counts, sizes, offsets at their maximum) are
    // refused with the file's name, before anything large is allocated. (A
    // huge task count alone is consistent; the merge refuses the band.)
    const std::size_t shift = 4 + length;  // the fields after the identity
    // The warp presets (a count, then per preset a name's length and text
    // and a draw count) come before the frame's size, at `shape`.
    std::uint32_t presets = 0;
    std::memcpy(&presets, bytes.data() + 16 + shift, 4);
    REQUIRE(presets <= 4);
    std::size_t shape = 20 + shift;
    for (std::uint32_t p = 0; p < presets; ++p) {
        std::uint32_t name = 0;
        std::memcpy(&name, bytes.data() + shape, 4);
        REQUIRE(name < 200);
        shape += 4 + name + 4;
    }
    for (const std::size_t at : std::initializer_list<std::size_t>{16, 16 + shift, 20 + shift, shape, shape + 4, shape + 16,
                                                                   shape + 24, shape + 40}) {
        CAPTURE(at);
        std::string bad = bytes;
        for (std::size_t k = at; k < at + 8; ++k) bad[k] = static_cast<char>(0xFF);
        std::ofstream(frame, std::ios::binary | std::ios::trunc).write(bad.data(), static_cast<std::streamsize>(bad.size()));
        CHECK_THROWS_WITH_AS((void)read_frame_file(frame.string(), identity, {48, 48}), doctest::Contains(frame.string().c_str()),
                             InputError);
    }
    // A frame larger than the config's (here 40000 x 40000, with the file's
    // few items inside it) is refused at its size field, before the merge
    // would allocate the whole frame.
    {
        std::string big = bytes;
        const std::int32_t side = 40000;
        std::memcpy(big.data() + shape, &side, 4);
        std::memcpy(big.data() + shape + 4, &side, 4);
        std::ofstream(frame, std::ios::binary | std::ios::trunc).write(big.data(), static_cast<std::streamsize>(big.size()));
        const std::string refused = frame.string() + ": byte " + std::to_string(shape) +
                                    ": a 40000 x 40000 frame, the config's is a 48 x 48 frame";
        CHECK_THROWS_WITH_AS((void)read_frame_file(frame.string(), identity, {48, 48}), refused.c_str(), InputError);
        has(merge_error({s0.string(), s1.string()}), "a 40000 x 40000 frame, the config's is a 48 x 48 frame");
        CHECK_THROWS_WITH_AS((void)read_frame_file(frame.string(), identity, {}),
                             doctest::Contains("the config's is a ray list"), InputError);
    }
    // Calibration does not shard.
    CHECK(simulate({"calibrate", "configs/runs/fig3_bundles.json", "--shard", "0/2", "--out", fresh("cal").string()}) == 2);
}

TEST_CASE("shard merge: checks what it merges (frame identities, every shard's points, --out not an input)") {
    const std::vector<std::string> base = {kTiny, "--set", "output.images=false", "--set", "output.rays=false",
                                           "--set", "workload.width=16", "--set", "workload.height=16"};
    const auto shard = [&](const fs::path& out, const std::string& spec, std::vector<std::string> extra = {}) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        a.insert(a.end(), {"--shard", spec, "--out", out.string()});
        return simulate(a);
    };
    const auto merge_error = [&](std::vector<std::string> args) {
        args.insert(args.begin(), "merge");
        args.push_back("--quiet");
        try {
            (void)run_merge(parse_cli(args));
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    const fs::path s0 = fresh("id_s0"), s1 = fresh("id_s1"), seed = fresh("id_seed");
    REQUIRE(shard(s0, "0/2") == 0);
    REQUIRE(shard(s1, "1/2") == 0);
    REQUIRE(shard(seed, "1/2", {"--set", "scene.seed=7"}) == 0);
    const fs::path ref = s1 / "frames" / "0_1_ref.bin", obb = s1 / "frames" / "0_1_obb.bin";
    REQUIRE(fs::exists(ref));
    REQUIRE(fs::exists(obb));
    // Swapped methods: the ref file holds obb's frame.
    fs::rename(ref, s1 / "frames" / "tmp.bin");
    fs::rename(obb, ref);
    fs::rename(s1 / "frames" / "tmp.bin", obb);
    std::string e = merge_error({s0.string(), s1.string(), "--out", fresh("id_out").string()});
    CHECK(e.find(ref.string() + ": byte ") == 0);
    CHECK(e.find("a frame of config ") != std::string::npos);
    CHECK(e.find(", method obb, point 0, band 1 of 2; the merge expects config ") != std::string::npos);
    CHECK(e.find(", method ref, point 0, band 1 of 2") != std::string::npos);
    // A band of a run with another seed, under the right name.
    fs::copy_file(seed / "frames" / "0_1_ref.bin", ref, fs::copy_options::overwrite_existing);
    e = merge_error({s0.string(), s1.string(), "--out", fresh("id_out").string()});
    CHECK(e.find(ref.string() + ": byte ") == 0);
    CHECK(e.find(", method ref, point 0, band 1 of 2; the merge expects") != std::string::npos);
    // shard.json's config edited (the merge plans from it): refused.
    REQUIRE(shard(fresh("id_s1"), "1/2") == 0);
    nlohmann::json manifest = nlohmann::json::parse(slurp(s0 / "shard.json"));
    nlohmann::json edited = nlohmann::json::parse(manifest["config_text"].get<std::string>());
    edited["scene"]["seed"] = 7;
    manifest["config_text"] = edited.dump();
    write_file_atomically((s0 / "shard.json").string(), manifest.dump());
    nlohmann::json other = nlohmann::json::parse(slurp(s1 / "shard.json"));
    other["config_text"] = manifest["config_text"];
    write_file_atomically((s1 / "shard.json").string(), other.dump());
    e = merge_error({s0.string(), s1.string(), "--out", fresh("id_out").string()});
    CHECK(e.find(s0.string() + "/shard.json: /config_hash: ") == 0);
    // Every shard's sweep point count, not only the first's.
    REQUIRE(shard(fresh("id_s0"), "0/2") == 0);
    REQUIRE(shard(fresh("id_s1"), "1/2") == 0);
    other = nlohmann::json::parse(slurp(s1 / "shard.json"));
    other["points"] = 2;
    write_file_atomically((s1 / "shard.json").string(), other.dump());
    e = merge_error({s0.string(), s1.string(), "--out", fresh("id_out").string()});
    CHECK(e.find(s1.string() + "/shard.json: /points: 2 sweep points") == 0);
    // --out equal to an input is refused before anything is emptied.
    REQUIRE(shard(fresh("id_s1"), "1/2") == 0);
    e = merge_error({s0.string(), s1.string(), "--out", s1.string(), "--force"});
    CHECK(e == "simulate merge: --out " + s1.string() + ": is the shard directory " + s1.string() +
                   " it merges: choose another --out");
    CHECK(fs::exists(s1 / "shard.json"));
    e = merge_error({s0.string(), s1.string(), "--out", (s0 / "frames").string(), "--force"});
    CHECK(e.find("is inside the shard directory " + s0.string()) != std::string::npos);
    CHECK(merge_error({s0.string(), s1.string(), "--out", fresh("id_out").string()}) == "(no error)");
}

}  // namespace RTCSIM_TEST_FILE
