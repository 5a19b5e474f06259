// Break-even maps' interval: a map of two methods whose cycles differ by one
// uncertain cost. ref costs 10 x (x: the swept tlas_box_test), obb 5 x the
// context switch, drawn around 200 with a log-variance of 0.09. Break-even at
// x = 100; the draws put it anywhere between half their 5th and 95th
// percentile switch, and exactly those cells must be in doubt.
#include "sim/execution/interrupt.h"
#include "sim/hardware/uncertainty/cost_uncertainty.h"
#include "sim/report/report.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

MethodRun counted(const std::string& name, Event e, std::uint64_t n) {
    MethodRun m;
    m.method = name;
    m.frame.totals.n[static_cast<std::size_t>(e)] = n;
    return m;
}

RunResult two_method_run(int draws) {
    nlohmann::json p = nlohmann::json::parse(read_text_file(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/turing-per-ray-guess.json"));
    p["uncertainty"] = {{"source", "test"},
                        {"parameters", {{{"events", {"context_switch"}}, {"tie", "value"}, {"value", 200}, {"min", 20}, {"max", 2000}, {"free", true}}}},
                        {"covariance", {{0.09}}}};
    RunResult r;
    r.config.name = "band";
    r.config.uncertainty.draws = draws;
    r.config.uncertainty.seed = 5;
    r.costs.push_back(parse_cost_model(p.dump(), "p.json"));
    r.methods.push_back(counted("ref", Event::TlasBoxTest, 10));
    r.methods.push_back(counted("obb", Event::ContextSwitch, 5));
    BreakEvenSpec s;
    s.name = "m";
    s.preset = r.costs[0].name;
    s.x = {{Event::TlasBoxTest}, 1.0, 1e4, false};
    s.y = {{Event::BlasBoxTest}, 1.0, 10.0, false};  // no method counts it: every row alike
    s.cells = 40;
    r.config.break_even.push_back(s);
    return r;
}

}  // namespace

TEST_CASE("break-even band: the cells in doubt are where the draws move the break-even, by hand") {
    const RunResult r = two_method_run(21);
    const BreakEvenGrid g = break_even_grid(r, r.config.break_even[0]);
    REQUIRE(g.draws == 21);
    REQUIRE(g.band_lo.size() == 1600);
    // 21 draws: the 5th and 95th percentiles are order statistics 1 and 19
    // (no interpolation), so a monotone function of the switch keeps them.
    std::vector<double> sw;
    for (const CostModel& m : draw_cost_models(r.costs[0], 21, 5)) sw.push_back(m[Event::ContextSwitch]);
    std::sort(sw.begin(), sw.end());
    const double lo_x = 5.0 * sw[1] / 10.0, hi_x = 5.0 * sw[19] / 10.0;
    REQUIRE(lo_x < 100.0);
    REQUIRE(hi_x > 100.0);
    int doubtful = 0;
    for (int ix = 0; ix < 40; ++ix) {
        const double x = std::pow(1e4, (ix + 0.5) / 40);  // cell centre on the log axis
        CAPTURE(x);
        for (int iy = 0; iy < 40; iy += 13) {
            const auto i = static_cast<std::size_t>(iy * 40 + ix);
            CHECK(g.winner[i] == (x < 100.0 ? 0 : 1));
            CHECK(g.uncertain(i) == (x >= lo_x && x <= hi_x));
            // The band's low end: the winner's lead under the 5th-percentile draw.
            const double low = x < 100.0 ? 5.0 * sw[1] / (10.0 * x) : 10.0 * x / (5.0 * sw[19]);
            CHECK(g.band_lo[i] == doctest::Approx(std::min(low, g.margin[i])));
        }
        doubtful += g.uncertain(static_cast<std::size_t>(ix));
    }
    CHECK(doubtful >= 3);  // the band is wider than a cell: the test can see its edges
    // The mark (the preset's own tlas_box_test) and the report's summary.
    const nlohmann::ordered_json j = break_even_json(r);
    REQUIRE(j.size() == 1);
    CHECK(j[0]["mark"]["winner"] == "ref");
    CHECK(j[0]["uncertain_share"].get<double>() == doctest::Approx(doubtful / 40.0));
    CHECK(j[0]["mark"]["lead_interval"][0].get<double>() <= j[0]["mark"]["lead"].get<double>());
    // Drawn: a hatched cell has the hatch's dark pixels, a sure one none.
    BreakEvenOptions o;
    o.cell_pixels = 10;
    const Image img = render_break_even(g, o);
    const auto dark = [&](int ix) {  // map origin (70, 40); the bottom row
        int n = 0;
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 10; ++x) n += img.get(70 + ix * 10 + x, 40 + 39 * 10 + y) == Rgb{40, 40, 40};
        return n;
    };
    const int in_band = static_cast<int>(std::log10(lo_x) / 4.0 * 40.0) + 1;
    CHECK(g.uncertain(static_cast<std::size_t>(in_band)));
    CHECK(dark(in_band) > 0);
    CHECK(dark(0) == 0);
}

TEST_CASE("break-even band: without draws no cell is in doubt") {
    const RunResult r = two_method_run(0);
    const BreakEvenGrid g = break_even_grid(r, r.config.break_even[0]);
    CHECK(g.draws == 0);
    CHECK(g.band_lo.empty());
    for (std::size_t i = 0; i < g.winner.size(); ++i) CHECK_FALSE(g.uncertain(i));
    CHECK(break_even_json(r)[0]["uncertain_share"].is_null());
}

TEST_CASE("break-even maps: a stop request ends a long map between rows (issue 56)") {
    // Was: no poll; Python's KeyboardInterrupt came 92 s after the signal.
    const RunResult r = two_method_run(21);
    request_interrupt();
    CHECK_THROWS_AS((void)break_even_grids(r), Interrupted);
    clear_interrupt();
    const BreakEvenGrids grids = break_even_grids(r);
    REQUIRE(grids.size() == 1);
    // The report's summary from the same grids is the one computed afresh.
    CHECK(break_even_json(r, grids) == break_even_json(r));
}

}  // namespace RTCSIM_TEST_FILE
