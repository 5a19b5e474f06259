// Image: a plain 8-bit RGB raster (row 0 = top) with the few drawing
// primitives the reports need (pixel access, fill, rectangles, blit), PNG
// output through stb_image_write, and the float framebuffer -> sRGB
// conversion used for the shaded render. Kept dependency-free so heat maps,
// text and renders all share one pixel type.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rtc {

struct Rgb {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;

    friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  // width * height * 3 bytes, row-major, row 0 = top

    Image() = default;
    // Throws std::invalid_argument for negative sizes.
    Image(int width, int height, Rgb background = {0, 0, 0});

    [[nodiscard]] bool contains(int x, int y) const {
        return x >= 0 && y >= 0 && x < width && y < height;
    }
    // Unchecked in release builds beyond an assert; callers clip first.
    [[nodiscard]] Rgb get(int x, int y) const;
    void set(int x, int y, Rgb c);
    // Writes only when (x, y) is inside; drawing code relies on this clipping.
    void set_clipped(int x, int y, Rgb c) {
        if (contains(x, y)) set(x, y, c);
    }
    void fill(Rgb c);
    // Fills [x, x+w) x [y, y+h), clipped to the image.
    void fill_rect(int x, int y, int w, int h, Rgb c);
    // One-pixel outline of the rectangle [x, x+w) x [y, y+h), clipped.
    void stroke_rect(int x, int y, int w, int h, Rgb c);
    // Copies `src` with its top-left corner at (x, y), clipped.
    void blit(const Image& src, int x, int y);
};

// Writes `image` as an 8-bit RGB PNG. Throws rtc::InputError naming `path`
// when the image is empty or the file cannot be written.
void write_png(const Image& image, const std::string& path);

enum class ToneMap {
    Clamp,     // x -> min(x, 1)
    Reinhard,  // x -> x / (1 + x), per channel
};

struct ToneMapOptions {
    ToneMap op = ToneMap::Reinhard;  // the shaded render has unbounded radiance
    float exposure = 1.0f;           // linear scale applied before the operator
};

// Linear [0, 1] -> 8-bit sRGB (the piecewise sRGB transfer curve, not a bare
// 2.2 gamma). NaN and negative values map to 0.
[[nodiscard]] std::uint8_t linear_to_srgb8(float linear);

// Converts a linear float RGB framebuffer (width * height entries, row 0 =
// top) to an 8-bit sRGB image. Throws std::invalid_argument on size mismatch.
[[nodiscard]] Image tonemap_to_srgb(std::span<const glm::vec3> pixels, int width, int height,
                                    const ToneMapOptions& options = {});

}  // namespace rtc
