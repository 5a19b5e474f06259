// Colour-map tables: evenly spaced control points of matplotlib's viridis and
// inferno (as published, e.g. R's viridisLite) and ColorBrewer's 11-class
// RdBu, reversed so low = blue. Linear interpolation between neighbours.
#include "sim/plot/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

namespace rtc {
namespace {

constexpr std::array<Rgb, 9> kViridis{{
    {0x44, 0x01, 0x54}, {0x47, 0x2D, 0x7B}, {0x3B, 0x52, 0x8B}, {0x2C, 0x72, 0x8E},
    {0x21, 0x90, 0x8C}, {0x27, 0xAD, 0x81}, {0x5D, 0xC8, 0x63}, {0xAA, 0xDC, 0x32},
    {0xFD, 0xE7, 0x25},
}};

constexpr std::array<Rgb, 10> kInferno{{
    {0x00, 0x00, 0x04}, {0x1B, 0x0C, 0x42}, {0x4B, 0x0C, 0x6B}, {0x78, 0x1C, 0x6D},
    {0xA5, 0x2C, 0x60}, {0xCF, 0x44, 0x46}, {0xED, 0x69, 0x25}, {0xFB, 0x9A, 0x06},
    {0xF7, 0xD0, 0x3C}, {0xFC, 0xFF, 0xA4},
}};

constexpr std::array<Rgb, 11> kBlueWhiteRed{{
    {0x05, 0x30, 0x61}, {0x21, 0x66, 0xAC}, {0x43, 0x93, 0xC3}, {0x92, 0xC5, 0xDE},
    {0xD1, 0xE5, 0xF0}, {0xF7, 0xF7, 0xF7}, {0xFD, 0xDB, 0xC7}, {0xF4, 0xA5, 0x82},
    {0xD6, 0x60, 0x4D}, {0xB2, 0x18, 0x2B}, {0x67, 0x00, 0x1F},
}};

std::span<const Rgb> table(Colormap map) {
    switch (map) {
        case Colormap::Viridis: return kViridis;
        case Colormap::Inferno: return kInferno;
        case Colormap::BlueWhiteRed: return kBlueWhiteRed;
    }
    return kViridis;
}

std::uint8_t lerp8(std::uint8_t a, std::uint8_t b, double f) {
    return static_cast<std::uint8_t>(std::lround(a + (static_cast<double>(b) - a) * f));
}

}  // namespace

Rgb colormap_at(Colormap map, double t) {
    if (std::isnan(t)) return kNoDataGrey;
    const std::span<const Rgb> lut = table(map);
    const double x = std::clamp(t, 0.0, 1.0) * static_cast<double>(lut.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(x), lut.size() - 2);
    const double f = x - static_cast<double>(i);
    const Rgb a = lut[i], b = lut[i + 1];
    return {lerp8(a.r, b.r, f), lerp8(a.g, b.g, f), lerp8(a.b, b.b, f)};
}

const char* colormap_name(Colormap map) {
    switch (map) {
        case Colormap::Viridis: return "viridis";
        case Colormap::Inferno: return "inferno";
        case Colormap::BlueWhiteRed: return "blue-white-red";
    }
    return "?";
}

}  // namespace rtc
