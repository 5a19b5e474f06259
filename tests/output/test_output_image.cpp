// Tests for sim/image (pixels, PNG round trip, tone mapping, write errors)
// and sim/text_raster (ink lands inside the measured box, scaling, alignment).
#include "core/input_error.h"
#include "sim/plot/image.h"
#include "sim/plot/text_raster.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

namespace {

std::string temp_path(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("rtcsim_" + std::to_string(getpid()) + "_" + name)).string();
}

int ink_count(const rtc::Image& img, rtc::Rgb background) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) n += img.get(x, y) != background;
    return n;
}

}  // namespace

TEST_CASE("output image: set, get, fill_rect clipping and blit") {
    rtc::Image img(4, 3, {1, 2, 3});
    CHECK(img.rgb.size() == 36);
    CHECK(img.get(3, 2) == rtc::Rgb{1, 2, 3});
    img.fill_rect(-5, -5, 7, 7, {9, 9, 9});  // covers x, y in [0, 2)
    CHECK(img.get(1, 1) == rtc::Rgb{9, 9, 9});
    CHECK(img.get(2, 1) == rtc::Rgb{1, 2, 3});
    rtc::Image small(2, 2, {200, 0, 0});
    img.blit(small, 3, 2);  // only (3, 2) lands inside
    CHECK(img.get(3, 2) == rtc::Rgb{200, 0, 0});
    CHECK(img.get(2, 2) == rtc::Rgb{1, 2, 3});
    img.set_clipped(10, 10, {0, 0, 0});  // ignored, no crash
    CHECK_THROWS_AS(rtc::Image(-1, 2), std::invalid_argument);
}

TEST_CASE("output image: PNG written and read back with the same size and pixels") {
    rtc::Image img(3, 2, {0, 0, 0});
    img.set(0, 0, {255, 0, 0});
    img.set(1, 0, {0, 255, 0});
    img.set(2, 0, {0, 0, 255});
    img.set(0, 1, {10, 20, 30});
    img.set(2, 1, {255, 255, 255});
    const std::string path = temp_path("roundtrip.png");
    rtc::write_png(img, path);
    int w = 0, h = 0, comp = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &comp, 3);
    REQUIRE(data != nullptr);
    CHECK(w == 3);
    CHECK(h == 2);
    CHECK(comp == 3);
    const std::vector<unsigned char> got(data, data + 18);
    stbi_image_free(data);
    std::filesystem::remove(path);
    CHECK(got == img.rgb);
}

TEST_CASE("output image: write_png to an unwritable path throws InputError naming the path") {
    const std::string path = "/nonexistent-rtcsim-dir/sub/out.png";
    try {
        rtc::write_png(rtc::Image(2, 2), path);
        FAIL("expected InputError");
    } catch (const rtc::InputError& e) {
        CHECK(std::string(e.what()).find(path) != std::string::npos);
    }
    CHECK_THROWS_AS(rtc::write_png(rtc::Image(), temp_path("empty.png")), rtc::InputError);
}

TEST_CASE("output image: sRGB conversion and tone mapping") {
    CHECK(rtc::linear_to_srgb8(0.0f) == 0);
    CHECK(rtc::linear_to_srgb8(1.0f) == 255);
    CHECK(rtc::linear_to_srgb8(0.5f) == 188);  // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
    CHECK(rtc::linear_to_srgb8(std::nanf("")) == 0);
    CHECK(rtc::linear_to_srgb8(-1.0f) == 0);

    const std::vector<glm::vec3> fb{{0.0f, 1.0f, 3.0f}, {1.0f, 1.0f, 1.0f}};
    const rtc::Image clamp = rtc::tonemap_to_srgb(fb, 2, 1, {rtc::ToneMap::Clamp, 1.0f});
    CHECK(clamp.get(0, 0) == rtc::Rgb{0, 255, 255});
    const rtc::Image reinhard = rtc::tonemap_to_srgb(fb, 2, 1, {rtc::ToneMap::Reinhard, 1.0f});
    CHECK(reinhard.get(1, 0) == rtc::Rgb{188, 188, 188});  // 1 / (1 + 1) = 0.5
    CHECK(reinhard.get(0, 0).b > 188);                       // 3 / 4 is brighter, still < 255
    CHECK(reinhard.get(0, 0).b < 255);
    const rtc::Image exposed = rtc::tonemap_to_srgb(fb, 2, 1, {rtc::ToneMap::Clamp, 0.5f});
    CHECK(exposed.get(1, 0) == rtc::Rgb{188, 188, 188});
    CHECK_THROWS_AS((void)rtc::tonemap_to_srgb(fb, 3, 1), std::invalid_argument);
}

TEST_CASE("output text: ink lands inside the measured box, nowhere else") {
    const rtc::Rgb white{255, 255, 255};
    rtc::Image img(80, 40, white);
    const std::string text = "A1x";
    rtc::draw_text(img, 10, 5, text, {{0, 0, 0}, 1, rtc::TextAlign::Left});
    const int w = rtc::text_width(text), h = rtc::text_height(text);
    CHECK(w > 10);
    CHECK(h == 12);
    int inside = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            if (img.get(x, y) == white) continue;
            const bool in_box = x >= 10 && x < 10 + w && y >= 5 && y < 5 + h;
            CHECK(in_box);
            inside += in_box;
            CHECK(img.get(x, y) == rtc::Rgb{0, 0, 0});
        }
    CHECK(inside > 10);
}

TEST_CASE("output text: 2x scale quadruples the ink, right alignment ends at x") {
    const rtc::Rgb white{255, 255, 255};
    rtc::Image one(200, 60, white), two(200, 60, white);
    rtc::draw_text(one, 0, 0, "Heat 42", {{0, 0, 0}, 1});
    rtc::draw_text(two, 0, 0, "Heat 42", {{0, 0, 0}, 2});
    CHECK(ink_count(one, white) > 0);
    CHECK(ink_count(two, white) == 4 * ink_count(one, white));
    CHECK(rtc::text_width("Heat 42", 2) == 2 * rtc::text_width("Heat 42"));

    rtc::Image right(100, 20, white);
    rtc::draw_text(right, 60, 2, "99", {{0, 0, 0}, 1, rtc::TextAlign::Right});
    int max_x = -1, min_x = 1000;
    for (int y = 0; y < right.height; ++y)
        for (int x = 0; x < right.width; ++x)
            if (right.get(x, y) != white) max_x = std::max(max_x, x), min_x = std::min(min_x, x);
    CHECK(max_x < 60);
    CHECK(min_x >= 60 - rtc::text_width("99"));
    // Non-ASCII bytes are drawn as '?' instead of indexing outside the font.
    rtc::Image q(40, 20, white);
    rtc::draw_text(q, 0, 0, "\xC3\xA9", {{0, 0, 0}, 1});
    CHECK(ink_count(q, white) > 0);
}

}  // namespace RTCSIM_TEST_FILE
