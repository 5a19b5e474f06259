// Image implementation: clipped drawing, PNG output via stb_image_write
// (libstb-dev, already a build dependency), and tone mapping to sRGB.
#include "sim/plot/image.h"

#include "core/input_error.h"
#include "sim/util/json_file.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <zlib.h>

namespace {

// stb's PNG writer deflates with zlib (zlib1g-dev) rather than its own
// deflate: on the head frame's 800 x 800 heat maps about twice as fast, and
// the files 10-15 % smaller (stb level 8 against zlib level 6, measured on
// render.png and heat_cycles_ref.png). Returns a malloc'ed buffer, as stb
// frees it with STBIW_FREE (free).
unsigned char* zlib_deflate(unsigned char* data, int length, int* out_length, int /*stb quality*/) {
    uLongf size = compressBound(static_cast<uLong>(length));
    auto* out = static_cast<unsigned char*>(std::malloc(size));
    if (!out) return nullptr;
    if (compress2(out, &size, data, static_cast<uLong>(length), Z_DEFAULT_COMPRESSION) != Z_OK) {
        std::free(out);
        return nullptr;
    }
    *out_length = static_cast<int>(size);
    return out;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS zlib_deflate
#define STB_IMAGE_WRITE_IMPLEMENTATION
// Static linkage keeps the stb symbols private to this file, so another
// translation unit (or a test) including stb cannot collide with them.
#define STB_IMAGE_WRITE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace rtc {

Image::Image(int w, int h, Rgb background) : width(w), height(h) {
    if (w < 0 || h < 0) throw std::invalid_argument("Image: negative size");
    rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    fill(background);
}

Rgb Image::get(int x, int y) const {
    assert(contains(x, y));
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void Image::set(int x, int y, Rgb c) {
    assert(contains(x, y));
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    rgb[i] = c.r;
    rgb[i + 1] = c.g;
    rgb[i + 2] = c.b;
}

void Image::fill(Rgb c) {
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
        rgb[i] = c.r;
        rgb[i + 1] = c.g;
        rgb[i + 2] = c.b;
    }
}

void Image::fill_rect(int x, int y, int w, int h, Rgb c) {
    const int x0 = std::max(x, 0), y0 = std::max(y, 0);
    const int x1 = std::min(x + w, width), y1 = std::min(y + h, height);
    for (int yy = y0; yy < y1; ++yy)
        for (int xx = x0; xx < x1; ++xx) set(xx, yy, c);
}

void Image::stroke_rect(int x, int y, int w, int h, Rgb c) {
    if (w <= 0 || h <= 0) return;
    fill_rect(x, y, w, 1, c);
    fill_rect(x, y + h - 1, w, 1, c);
    fill_rect(x, y, 1, h, c);
    fill_rect(x + w - 1, y, 1, h, c);
}

void Image::blit(const Image& src, int x, int y) {
    for (int sy = 0; sy < src.height; ++sy)
        for (int sx = 0; sx < src.width; ++sx) set_clipped(x + sx, y + sy, src.get(sx, sy));
}

void write_png(const Image& image, const std::string& path) {
    if (image.width <= 0 || image.height <= 0)
        throw InputError(path + ": cannot write an empty image as PNG");
    // stb's own file writer ignores fwrite's and fclose's errors: the encoded
    // PNG goes through an OutputFile, which checks them (and renames the
    // finished file into place).
    OutputFile file(path);
    const auto sink = [](void* context, void* data, int size) {
        static_cast<OutputFile*>(context)->write_noexcept(data, static_cast<std::size_t>(size));
    };
    const int ok = stbi_write_png_to_func(sink, &file, image.width, image.height, 3, image.rgb.data(),
                                          image.width * 3);
    if (!ok) throw InputError(path + ": cannot encode the PNG (out of memory?)");
    file.commit();
}

std::uint8_t linear_to_srgb8(float v) {
    if (!(v > 0.0f)) return 0;  // also catches NaN
    if (v >= 1.0f) return 255;
    const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(s * 255.0f));
}

Image tonemap_to_srgb(std::span<const glm::vec3> pixels, int width, int height,
                      const ToneMapOptions& options) {
    if (width < 0 || height < 0 ||
        pixels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        throw std::invalid_argument("tonemap_to_srgb: pixel count does not match width * height");
    auto map = [&](float x) {
        x *= options.exposure;
        if (!(x > 0.0f)) return 0.0f;
        if (std::isinf(x)) return 1.0f;
        return options.op == ToneMap::Reinhard ? x / (1.0f + x) : std::min(x, 1.0f);
    };
    Image out(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::vec3& p = pixels[static_cast<std::size_t>(y) * width + x];
            out.set(x, y, {linear_to_srgb8(map(p.x)), linear_to_srgb8(map(p.y)),
                           linear_to_srgb8(map(p.z))});
        }
    }
    return out;
}

}  // namespace rtc
