// Sampled simulation (docs/sampling.md): the tile sample's design (two
// tiles per stratum, each tile traced with probability 1/k, the same tiles
// for a seed), the estimators against hand-computed values and their
// coverage on a known population, and end to end: fraction 1 is the full
// run bit for bit, a sampled run traces exactly the sampled tiles of the
// full run and scales them by k, and it is the same at any thread count and
// when sharded and merged.
#include "core/input_error.h"
#include "sim/app/cli.h"
#include "sim/app/run_all.h"
#include "sim/app/simulate_main.h"
#include "sim/execution/tile_sample.h"
#include "sim/config/work_estimate.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <random>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kTiny = "tests/configs/tiny.json";
// tiny.json under a warp preset and a per-ray one, without the ray and hit files.
const std::vector<std::string> kTinyBoth = {"cost=[\"turing-calibrated\", \"../../configs/hw/turing-per-ray-guess.json\"]",
                                            "output.rays=false", "output.hits=false"};

fs::path fresh(const std::string& name) {
    const fs::path p = fs::path(RTCSIM_BINARY_DIR) / "sampling_test" / name;
    fs::remove_all(p);
    return p;
}

int simulate(std::vector<std::string> args, const char* threads = "2") {
    args.insert(args.end(), {"--quiet", "--threads", threads});
    return simulate_main(args);
}

std::vector<std::string> with_sets(std::vector<std::string> args, const std::vector<std::string>& sets) {
    for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
    return args;
}

nlohmann::json report(const fs::path& dir) {
    return nlohmann::json::parse(read_text_file((dir / "report.json").string()));
}

// report.json without what differs between identical runs (and, with
// `config`, the config as given, which names the sampling block).
nlohmann::json comparable(nlohmann::json j, bool config = false) {
    if (j.is_object()) {
        for (const char* k : {"provenance", "wall_seconds", "simulator"}) j.erase(k);
        if (config) j.erase("config");
        for (auto& [k, v] : j.items()) v = comparable(v, config);
    } else if (j.is_array()) {
        for (auto& v : j) v = comparable(v, config);
    }
    return j;
}

void check_same_outputs(const fs::path& a, const fs::path& b, bool config = false) {
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(a)) {
        if (!e.is_regular_file()) continue;
        const fs::path rel = fs::relative(e.path(), a);
        CAPTURE(rel.string());
        REQUIRE(fs::exists(b / rel));
        ++files;
        if (rel.filename() == "report.json")
            CHECK(comparable(nlohmann::json::parse(read_text_file(e.path().string())), config) ==
                  comparable(nlohmann::json::parse(read_text_file((b / rel).string())), config));
        else
            CHECK(read_text_file(e.path().string()) == read_text_file((b / rel).string()));
    }
    CHECK(files >= 5);
}

RunResult run_in_process(const std::vector<std::string>& sets, unsigned threads = 2) {
    const RunPlan plan = plan_config_text(kTiny, read_text_file(kTiny), sets, {});
    RunContext ctx;
    ctx.threads = threads;
    ctx.quiet = true;
    return run_point(plan, 0, ctx);
}

}  // namespace

TEST_CASE("tile sample: two tiles per stratum of 2k, each tile with probability 1/k, fixed by the seed") {
    CHECK(sample_k(1.0) == 1);
    CHECK(sample_k(0.0625) == 16);
    CHECK(sample_k(0.1) == 10);
    CHECK(sample_k(0.3) == 3);
    CHECK(sample_k(0.75) == 1);
    CHECK_FALSE(TileSample::make(800, 800, 8, 4, {1.0, 1}));
    CHECK_FALSE(TileSample::make(800, 800, 8, 4, {0.7, 1}));  // rounds to k = 1: every tile

    const TileSample s = *TileSample::make(801, 803, 8, 4, {0.0625, 7});
    CHECK(s.k() == 16);
    CHECK(s.tiles_x() == 101);
    CHECK(s.tiles_y() == 201);
    CHECK(s.tiles() == 101u * 201u);
    // Blocks of 4 x 8 tiles (32 x 32 pixels): 26 x 26 of them.
    CHECK(s.block_width() == 4);
    CHECK(s.block_height() == 8);
    CHECK(s.blocks_x() == 26);
    CHECK(s.strata() == 26u * 26u);
    REQUIRE(s.slots().size() == 2 * s.strata());
    std::size_t traced = 0;
    for (std::uint32_t ty = 0; ty < s.tiles_y(); ++ty)
        for (std::uint32_t tx = 0; tx < s.tiles_x(); ++tx) traced += s.traced(tx, ty);
    CHECK(traced == s.traced_tiles());
    for (std::size_t h = 0; h < s.strata(); ++h) {
        const std::uint32_t a = s.slots()[2 * h], b = s.slots()[2 * h + 1];
        CAPTURE(h);
        const std::uint32_t bx = static_cast<std::uint32_t>(h) % 26, by = static_cast<std::uint32_t>(h) / 26;
        // Real tiles of the stratum's block, distinct and in order; padding
        // (kEmpty) only in the blocks over the right or bottom edge.
        for (const std::uint32_t t : {a, b}) {
            if (t == TileSample::kEmpty) {
                CHECK((bx == 25 || by == 25));
                continue;
            }
            CHECK(t % s.tiles_x() / 4 == bx);
            CHECK(t / s.tiles_x() / 8 == by);
        }
        if (a != TileSample::kEmpty && b != TileSample::kEmpty) CHECK(a != b);
    }
    // The same seed draws the same tiles; another seed others.
    CHECK(TileSample::make(801, 803, 8, 4, {0.0625, 7})->slots() == s.slots());
    CHECK(TileSample::make(801, 803, 8, 4, {0.0625, 8})->slots() != s.slots());
    // Each position of a stratum is drawn with probability 2/L = 1/k: over
    // 4,000 seeds each of the 32 positions is drawn about 250 times.
    std::vector<int> drawn(32, 0);
    for (std::uint64_t seed = 0; seed < 4000; ++seed) {
        const TileSample t = *TileSample::make(32, 32, 8, 4, {0.0625, seed});  // one stratum of 4 x 8 tiles
        REQUIRE(t.strata() == 1);
        for (const std::uint32_t tile : t.slots()) ++drawn[tile];
    }
    for (int d : drawn) CHECK(std::abs(d - 250) < 60);  // 250 +/- 3.9 sigma
}

TEST_CASE("sampling estimators: hand-computed totals, ratios and t quantiles") {
    // Student's t, 0.975: 12.706 (1), 4.303 (2), 3.182 (3), 2.228 (10), 2.042 (30), 1.984 (100).
    CHECK(t_quantile_975(1) == doctest::Approx(12.706).epsilon(1e-4));
    CHECK(t_quantile_975(2) == doctest::Approx(4.303).epsilon(1e-4));
    CHECK(t_quantile_975(3) == doctest::Approx(3.182).epsilon(2e-3));
    CHECK(t_quantile_975(10) == doctest::Approx(2.228).epsilon(1e-3));
    CHECK(t_quantile_975(30.7) == doctest::Approx(2.042).epsilon(1e-3));  // rounded down
    CHECK(t_quantile_975(100) == doctest::Approx(1.984).epsilon(1e-3));
    // k = 4, strata (1, 3) and (2, 2): total 4 x 8 = 32, variance
    // k (k - 1) sum d^2 = 12 x 4 = 48; one stratum with spread: 1 dof.
    const SampledEstimate t = estimate_total({1, 3, 2, 2}, 4);
    CHECK(t.value == 32.0);
    CHECK(t.std_error == doctest::Approx(std::sqrt(48.0)));
    CHECK(t.dof == 1.0);
    CHECK(t.interval[0] == doctest::Approx(32.0 - 12.706 * std::sqrt(48.0)).epsilon(1e-4));
    // No spread: a zero-width interval.
    const SampledEstimate z = estimate_total({5, 5, 7, 7}, 4);
    CHECK(z.std_error == 0.0);
    CHECK(z.interval[0] == z.interval[1]);
    // Ratio: num (4, 2, 6, 6), den (2, 2, 3, 3): R = 18 / 10 = 1.8; e = num
    // - R den = (0.4, -1.6, 0.6, 0.6); d = (2.0, 0); variance of the e total
    // 12 x 4 = 48, over (k sum den)^2 = 40^2.
    const SampledEstimate r = estimate_ratio({4, 2, 6, 6}, {2, 2, 3, 3}, 4);
    CHECK(r.value == doctest::Approx(1.8));
    CHECK(r.std_error == doctest::Approx(std::sqrt(48.0) / 40.0));
    // Proportional tiles: the ratio is exact, whatever the spread.
    const SampledEstimate p = estimate_ratio({2, 8, 4, 6}, {1, 4, 2, 3}, 4);
    CHECK(p.value == doctest::Approx(2.0));
    CHECK(p.std_error == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(centred(t, 40.0).interval[0] == doctest::Approx(t.interval[0] + 8.0));
}

TEST_CASE("sampling estimators: 95 % intervals cover a known population's total and ratio") {
    // A frame of 100 x 200 tiles whose cost has a smooth trend, a bright
    // blob and noise; the method's cost is the baseline's / 1.5 plus noise.
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 1.0);
    const int tw = 100, th = 200;
    std::vector<double> base(static_cast<std::size_t>(tw) * th), other(base.size());
    double total_base = 0.0, total_other = 0.0;
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) {
            const double blob = std::exp(-((x - 40) * (x - 40) + (y - 120) * (y - 120)) / 200.0);
            const double b = 10.0 + 0.05 * x + 50.0 * blob + 2.0 * std::abs(noise(rng));
            const double o = b / (1.2 + 0.6 * blob) + std::abs(noise(rng));
            base[static_cast<std::size_t>(y) * tw + x] = b;
            other[static_cast<std::size_t>(y) * tw + x] = o;
            total_base += b;
            total_other += o;
        }
    const double ratio = total_base / total_other;
    int covered_total = 0, covered_ratio = 0;
    const int seeds = 400;
    for (int seed = 0; seed < seeds; ++seed) {
        // One "pixel" per tile: a 100 x 200 frame of 1 x 1 tiles.
        const TileSample s = *TileSample::make(tw, th, 1, 1, {1.0 / 16, static_cast<std::uint64_t>(seed)});
        const auto yb = s.tile_values(tw, th, [&](std::size_t i) { return base[i]; });
        const auto yo = s.tile_values(tw, th, [&](std::size_t i) { return other[i]; });
        const SampledEstimate t = estimate_total(yb, s.k());
        const SampledEstimate r = estimate_ratio(yb, yo, s.k());
        covered_total += t.interval[0] <= total_base && total_base <= t.interval[1];
        covered_ratio += r.interval[0] <= ratio && ratio <= r.interval[1];
    }
    CAPTURE(covered_total);
    CAPTURE(covered_ratio);
    CHECK(covered_total >= seeds * 90 / 100);
    CHECK(covered_ratio >= seeds * 90 / 100);
    CHECK(covered_total <= seeds);
}

TEST_CASE("sampled run: fraction 1 is the full run, bit for bit (numbers and files)") {
    const fs::path full = fresh("full"), one = fresh("one");
    REQUIRE(simulate(with_sets({kTiny, "--out", full.string()}, kTinyBoth)) == 0);
    REQUIRE(simulate(with_sets({kTiny, "--out", one.string(), "--sample", "1", "--sample-seed", "5"}, kTinyBoth)) == 0);
    // Every file the same; report.json also, but for its config as given.
    check_same_outputs(full, one, /*config=*/true);
    const nlohmann::json r = report(one);
    CHECK_FALSE(r.contains("sampling"));
    CHECK(r["config"]["sampling"]["fraction"] == 1);
    const std::string csv = read_text_file((one / "results.csv").string());
    CHECK(csv.find("speedup_high,sampling_low,sampling_high,is_calls") != std::string::npos);
}

TEST_CASE("sampled run: traces exactly the full run's sampled tiles and scales them by k") {
    const RunResult full = run_in_process(kTinyBoth);
    std::vector<std::string> sets = kTinyBoth;
    sets.insert(sets.end(), {"sampling.fraction=0.25", "sampling.seed=3"});
    const RunResult part = run_in_process(sets);
    REQUIRE(part.sample);
    const TileSample& s = *part.sample;
    CHECK(s.k() == 4);
    CHECK(s.tile_width() == 8);  // the warp preset's tile
    CHECK(s.tile_height() == 4);
    for (std::size_t mi = 0; mi < full.methods.size(); ++mi) {
        const MethodRun& f = full.methods[mi];
        const MethodRun& m = part.methods[mi];
        CAPTURE(m.method);
        REQUIRE(m.sampled);
        EventTotals traced;
        std::uint64_t pixels_traced = 0;
        const int w = f.frame.width, h = f.frame.height;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * w + x;
                const bool in = s.traced_pixel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
                CHECK((m.frame.pixel_counts[i].n == (in ? f.frame.pixel_counts[i].n : RayCounts{}.n)));
                CHECK(m.frame.warp[0].pixel_cycles[i] == (in ? f.frame.warp[0].pixel_cycles[i] : 0.0f));
                if (in) {
                    traced.add(f.frame.pixel_counts[i]);
                    ++pixels_traced;
                }
            }
        CHECK(pixels_traced == s.traced_tiles() * 32);
        for (std::size_t e = 0; e < kEventCount; ++e) CHECK(m.totals().n[e] == 4 * traced.n[e]);
        CHECK(m.rays() == 4 * m.frame.rays_traced);
        // The totals are estimates of the full run's, inside their intervals here.
        for (std::size_t p = 0; p < part.costs.size(); ++p) {
            REQUIRE(m.sampled->cycles[p]);
            const auto& i = m.sampled->cycles[p]->interval;
            CHECK(i[0] <= m.priced[p].total_cycles);
            CHECK(m.priced[p].total_cycles <= i[1]);
            CHECK(m.priced[p].total_cycles == doctest::Approx(m.sampled->cycles[p]->value));
        }
    }
    for (std::size_t p = 0; p < part.costs.size(); ++p) {
        const auto e = part.sampled_speedup("obb", p);
        REQUIRE(e);
        CHECK(e->value == part.speedup("obb", p));
        CHECK(e->interval[0] < e->value);
        CHECK(e->value < e->interval[1]);
        CHECK_FALSE(full.sampled_speedup("obb", p));
    }
}

TEST_CASE("sampled run: the same at any thread count, and sharded and merged") {
    const std::vector<std::string> sampled = {"--sample", "0.25", "--sample-seed", "11"};
    std::vector<std::string> base = {kTiny};
    base.insert(base.end(), sampled.begin(), sampled.end());
    for (const bool warp : {false, true}) {
        CAPTURE(warp);
        const std::vector<std::string> args = warp ? with_sets(base, kTinyBoth) : with_sets(base, {"output.rays=false"});
        const fs::path one = fresh("t1"), two = fresh("t2");
        std::vector<std::string> a1 = args, a2 = args;
        a1.insert(a1.end(), {"--out", one.string()});
        a2.insert(a2.end(), {"--out", two.string()});
        REQUIRE(simulate(a1, "1") == 0);
        REQUIRE(simulate(a2, "2") == 0);
        check_same_outputs(one, two);
        const nlohmann::json r = report(one);
        CHECK(r["sampling"]["fraction"] == 0.25);
        CHECK(r["sampling"]["seed"] == 11);
        CHECK(r["speedup_sampling_interval_over_ref"]["obb"].size() == r["cost_presets"].size());
        CHECK(r["methods"]["obb"]["events"]["ray"].contains("sampling_interval"));
        // Sharded in 3 bands of rows and merged: the single run's outputs.
        std::vector<std::string> merge = {"merge"};
        for (int i = 0; i < 3; ++i) {
            const fs::path shard = fresh("s" + std::to_string(i));
            std::vector<std::string> a = args;
            a.insert(a.end(), {"--shard", std::to_string(i) + "/3", "--out", shard.string()});
            REQUIRE(simulate(a) == 0);
            merge.push_back(shard.string());
        }
        const fs::path merged = fresh("merged");
        merge.insert(merge.end(), {"--out", merged.string()});
        REQUIRE(simulate(merge) == 0);
        check_same_outputs(one, merged);
    }
}

TEST_CASE("sampled run: config and CLI errors, and the fraction suggested for a target error") {
    CHECK_THROWS_WITH_AS((void)parse_cli({kTiny, "--sample", "0"}), doctest::Contains("--sample: expected a fraction"),
                         InputError);
    CHECK_THROWS_WITH_AS((void)parse_cli({kTiny, "--sample", "1.5"}), doctest::Contains("--sample"), InputError);
    CHECK_THROWS_WITH_AS((void)parse_cli({kTiny, "--target-error", "0.02"}), doctest::Contains("goes with --estimate"),
                         InputError);
    CHECK_THROWS_WITH_AS((void)plan_config_text(kTiny, read_text_file(kTiny), {"sampling.fraction=2"}, {}),
                         doctest::Contains("/sampling/fraction"), InputError);
    CHECK_THROWS_WITH_AS((void)plan_config_text(kTiny, read_text_file(kTiny), {"sampling.tiles=2"}, {}),
                         doctest::Contains("/sampling"), InputError);
    const CliOptions o = parse_cli({kTiny, "--sample", "0.0625", "--sample-seed", "4"});
    CHECK(o.sets == std::vector<std::string>{"sampling.fraction=0.0625", "sampling.seed=4"});
    // The rule: (1 - f) / f = (1 - f0) / f0 (target / pilot)^2.
    CHECK(suggested_k(64, 0.02, 0.02) == 64);
    CHECK(suggested_k(64, 0.04, 0.02) == 16);  // 1 + 63 / 4 = 16.75
    CHECK(suggested_k(16, 0.01, 0.02) == 61);  // 1 + 15 x 4 = 61: a smaller sample is enough
    CHECK(suggested_k(64, 0.2, 0.02) == 1);    // needs more than every tile: trace it whole
    CHECK(suggested_k(64, 0.0, 0.02) == 64);   // no spread seen: no smaller sample than the pilot's
}

TEST_CASE("sampled run: the work estimate (and --max-rays) counts the traced tiles' rays") {
    const RunPlan full = plan_config_text(kTiny, read_text_file(kTiny), {}, {});
    const RunPlan sampled = plan_config_text(kTiny, read_text_file(kTiny), {"sampling.fraction=0.0625"}, {});
    const WorkEstimate f = estimate_config_work(full.parsed.at(0));
    const WorkEstimate s = estimate_config_work(sampled.parsed.at(0));
    REQUIRE(f.rays > 0);
    CHECK(s.rays == doctest::Approx(f.rays / 16));
    CHECK(s.rays_detail.find("1/16 of the tiles") != std::string::npos);
    // tiny.json records its rays and hits: only the traced ones are kept;
    // the per-pixel arrays stay full-frame.
    CHECK(s.memory_bytes < f.memory_bytes);
    CHECK(s.memory_bytes > f.memory_bytes - 15.0 / 16 * f.rays * 64);
}

}  // namespace RTCSIM_TEST_FILE
