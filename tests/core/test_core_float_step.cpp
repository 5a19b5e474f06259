// float_step_up / float_step_down are std::nextafter towards +-infinity, for
// every kind of float: zeros, denormals, the largest finite, infinities, NaN
// and a million random bit patterns.
#include "core/float_step.h"

#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

bool same(float a, float b) {
    return std::isnan(a) ? std::isnan(b) : std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

}  // namespace

TEST_CASE("float steps: exactly std::nextafter towards +-infinity") {
    using L = std::numeric_limits<float>;
    std::vector<float> xs = {0.0f,         -0.0f,        L::denorm_min(), -L::denorm_min(), L::min(),
                             -L::min(),    L::max(),     -L::max(),       L::infinity(),    -L::infinity(),
                             L::quiet_NaN(), 1.0f,       -1.0f,           0.1f,             -3.5e-40f};
    std::mt19937 rng(5);
    for (int i = 0; i < 1000000; ++i) xs.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(rng())));
    std::size_t wrong_up = 0, wrong_down = 0;
    for (const float x : xs) {
        wrong_up += !same(float_step_up(x), std::nextafter(x, L::infinity()));
        wrong_down += !same(float_step_down(x), std::nextafter(x, -L::infinity()));
    }
    CHECK(wrong_up == 0);
    CHECK(wrong_down == 0);
    // Spot checks that do not lean on nextafter.
    CHECK(same(float_step_up(-L::denorm_min()), -0.0f));
    CHECK(same(float_step_down(L::denorm_min()), 0.0f));
    CHECK(same(float_step_up(L::max()), L::infinity()));
    CHECK(same(float_step_up(-L::infinity()), -L::max()));
    CHECK(float_step_up(1.0f) > 1.0f);
    CHECK(float_step_down(1.0f) < 1.0f);
}

}  // namespace RTCSIM_TEST_FILE
