// Break-even maps: the renderer colours each cell by its winner (strength by
// margin, grey where none runs) and the config block is checked with paths.
#include "core/input_error.h"
#include "sim/config/run_config.h"
#include "sim/plot/break_even.h"

#include <doctest/doctest.h>

#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("break-even map: winners, margins and empty cells are drawn") {
    BreakEvenGrid g;
    g.nx = 2, g.ny = 1;
    g.winner = {0, -1};
    g.margin = {4.0, 1.0};
    g.methods = {"ref"};
    g.x_lo = 1, g.x_hi = 100, g.y_lo = 1, g.y_hi = 10;
    BreakEvenOptions o;
    o.cell_pixels = 10;
    const Image img = render_break_even(g, o);
    CHECK(img.width > 20);
    // Map origin at (70, 40): cell 0 full colour (margin >= 2x), cell 1 grey.
    CHECK(img.get(75, 45) == Rgb{0, 114, 178});
    CHECK(img.get(85, 45) == Rgb{128, 128, 128});
    o.scale = 2;  // the whole picture magnified: same cells at twice the coordinates
    const Image big = render_break_even(g, o);
    CHECK(big.width == 2 * img.width);
    CHECK(big.height == 2 * img.height);
    CHECK(big.get(151, 91) == Rgb{0, 114, 178});
    CHECK(big.get(171, 91) == Rgb{128, 128, 128});
    g.winner.pop_back();
    CHECK_THROWS_AS((void)render_break_even(g, o), std::invalid_argument);
}

TEST_CASE("break-even map: the config block names unknown events and bad ranges by path") {
    nlohmann::json c = {{"scene", {{"type", "bundle"}}},
                        {"break_even", {{{"name", "m"}, {"preset", "p"},
                                         {"x", {{"events", {"context_switch"}}, {"min", 1}, {"max", 10}}},
                                         {"y", {{"events", {"context_swich"}}, {"min", 1}, {"max", 10}}}}}}};
    CHECK_THROWS_WITH_AS((void)parse_run_config(c, "x.json"),
                         doctest::Contains("x.json: /break_even/0/y/events/0: unknown event"), InputError);
    c["break_even"][0]["y"]["events"] = {"obb_box_test"};
    c["break_even"][0]["y"]["max"] = 0.5;
    CHECK_THROWS_WITH_AS((void)parse_run_config(c, "x.json"), doctest::Contains("/break_even/0/y/max"), InputError);
    c["break_even"][0]["y"]["max"] = 5;
    // The preset is one of the run's, checked with the presets loaded.
    CHECK_THROWS_WITH_AS((void)parse_run_config(c, "x.json"),
                         "x.json: /break_even: preset \"p\" is not one of the run's cost presets", InputError);
    c["break_even"][0]["preset"] = "turing-calibrated";
    const RunConfig r = parse_run_config(c, "x.json");
    REQUIRE(r.break_even.size() == 1);
    CHECK(r.break_even[0].y.events == std::vector<Event>{Event::ObbBoxTest});
    CHECK(r.break_even[0].cells == 48);
}

TEST_CASE("break-even map: the preset's own point is marked, with five ticks per axis") {
    BreakEvenGrid g;
    g.nx = 2, g.ny = 1;
    g.winner = {0, 0};
    g.margin = {4.0, 4.0};
    g.methods = {"ref"};
    g.x_lo = 1, g.x_hi = 100, g.y_lo = 1, g.y_hi = 10;
    BreakEvenOptions o;
    o.cell_pixels = 10;
    const Image plain = render_break_even(g, o);
    g.has_mark = true;
    g.mark_x = 10, g.mark_y = std::sqrt(10.0);  // the middle of both log axes
    g.mark_label = "preset";
    const Image marked = render_break_even(g, o);
    // Map origin (70, 40), 20 x 10 pixels: the middle is (80, 45).
    CHECK(plain.get(80, 45) == Rgb{0, 114, 178});
    CHECK(marked.get(80, 45) == Rgb{0, 0, 0});
    g.mark_x = 1000;  // off the map: not drawn
    CHECK(render_break_even(g, o).get(80, 45) == Rgb{0, 114, 178});
}

TEST_CASE("break-even map: a scale axis and a method subset are read, unknown methods refused by path") {
    nlohmann::json c = {{"scene", {{"type", "bundle"}}},
                        {"methods", {"ref", "obb"}},
                        {"break_even", {{{"name", "m"}, {"preset", "turing-calibrated"}, {"methods", {"ref", "obb"}},
                                         {"x", {{"events", {"op_fma", "op_load"}}, {"scale", true}, {"min", 0.1}, {"max", 10}}},
                                         {"y", {{"events", {"context_switch"}}, {"min", 1}, {"max", 10}}}}}}};
    const RunConfig r = parse_run_config(c, "x.json");
    REQUIRE(r.break_even.size() == 1);
    CHECK(r.break_even[0].x.scale);
    CHECK_FALSE(r.break_even[0].y.scale);
    CHECK(r.break_even[0].methods == std::vector<std::string>{"ref", "obb"});
    c["break_even"][0]["methods"] = {"ref", "lss"};
    CHECK_THROWS_WITH_AS((void)parse_run_config(c, "x.json"),
                         doctest::Contains("x.json: /break_even/0/methods/1: \"lss\" is not one of the run's methods"), InputError);
}

}  // namespace RTCSIM_TEST_FILE
