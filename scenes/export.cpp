// Strand export (see export.h).
#include "scenes/export.h"

#include "core/input_error.h"

#include <charconv>
#include <cstring>
#include <fstream>
#include <string>

namespace rtc {

namespace {
void append_float(std::string& s, float x) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest round trip
    s.append(buf, r.ptr);
}
template <class T>
void append_raw(std::string& s, T v) {
    char buf[sizeof(T)];
    std::memcpy(buf, &v, sizeof(T));  // little endian host, as the format wants
    s.append(buf, sizeof(T));
}
void write_all(const std::filesystem::path& file, const std::string& bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(file.string() + ": cannot open for writing");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw InputError(file.string() + ": write failed");
}
}  // namespace

void write_txt(const Strands& s, const std::filesystem::path& file) {
    std::string text = "# rtcsim curves: one \"x y z r\" line per point, blank line between strands\n";
    text.reserve(text.size() + s.points.size() * 48);
    for (std::size_t i = 0; i < s.strand_count(); ++i) {
        if (i > 0) text += '\n';
        for (std::uint32_t k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
            append_float(text, s.points[k].x);
            text += ' ';
            append_float(text, s.points[k].y);
            text += ' ';
            append_float(text, s.points[k].z);
            text += ' ';
            append_float(text, s.radii[k]);
            text += '\n';
        }
    }
    write_all(file, text);
}

void write_hair(const Strands& s, const std::filesystem::path& file) {
    std::string bytes;
    bytes.reserve(128 + 2 * s.strand_count() + 16 * s.points.size());
    bytes.append("HAIR", 4);
    append_raw(bytes, static_cast<std::uint32_t>(s.strand_count()));
    append_raw(bytes, static_cast<std::uint32_t>(s.points.size()));
    append_raw(bytes, std::uint32_t{1 | 2 | 4});  // segments, points, thickness
    append_raw(bytes, std::uint32_t{0});           // default segments (unused: array present)
    append_raw(bytes, 0.0f);                        // default thickness (unused)
    append_raw(bytes, 1.0f);                        // default transparency
    for (int i = 0; i < 3; ++i) append_raw(bytes, 0.5f);  // default colour
    char info[88] = {};
    std::strncpy(info, "written by rtcsim", sizeof info - 1);
    bytes.append(info, sizeof info);
    for (std::size_t i = 0; i < s.strand_count(); ++i) {
        const std::uint32_t n = s.offsets[i + 1] - s.offsets[i];
        if (n == 0 || n - 1 > 0xFFFFu)
            throw InputError(file.string() + ": strand " + std::to_string(i) + " has " +
                             std::to_string(n) + " points; HAIR needs 1 to 65,536");
        append_raw(bytes, static_cast<std::uint16_t>(n - 1));
    }
    for (const Vec3& p : s.points) {
        append_raw(bytes, p.x);
        append_raw(bytes, p.y);
        append_raw(bytes, p.z);
    }
    for (float r : s.radii) append_raw(bytes, 2.0f * r);
    write_all(file, bytes);
}

}  // namespace rtc
