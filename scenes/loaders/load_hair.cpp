// Cem Yuksel's HAIR format (http://www.cemyuksel.com/research/hairmodels/):
// 128-byte header, then the arrays named by the flags, in flag order. The
// expected file size follows from the header, so any disagreement between the
// counts and the size is caught before reading a single point.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/generators/strand_builder.h"

namespace rtc {

namespace {
constexpr std::uint32_t kHasSegments = 1u << 0;
constexpr std::uint32_t kHasPoints = 1u << 1;
constexpr std::uint32_t kHasThickness = 1u << 2;
constexpr std::uint32_t kHasTransparency = 1u << 3;
constexpr std::uint32_t kHasColor = 1u << 4;
constexpr std::size_t kHeaderBytes = 128;
}  // namespace

LoadedCurves load_hair(const std::filesystem::path& file) {
    const ByteReader in(read_file_bytes(file), file.string());
    in.require(0, kHeaderBytes, "HAIR header");
    if (std::memcmp(in.data(0), "HAIR", 4) != 0) in.fail(0, "bad magic (expected \"HAIR\")");
    const auto strands = in.get<std::uint32_t>(4);
    const auto points = in.get<std::uint32_t>(8);
    const auto flags = in.get<std::uint32_t>(12);
    const auto default_segments = in.get<std::uint32_t>(16);
    const auto default_thickness = in.get<float>(20);
    if (!(flags & kHasPoints)) in.fail(12, "flags say the file has no points array");
    if (flags >> 5) in.fail(12, "unknown flag bits " + std::to_string(flags));

    // Expected layout; sizes in 64 bits so huge counts cannot wrap around.
    const std::uint64_t s = strands, p = points;
    const std::uint64_t seg_bytes = (flags & kHasSegments) ? 2 * s : 0;
    const std::uint64_t expected = kHeaderBytes + seg_bytes + 12 * p +
                                   ((flags & kHasThickness) ? 4 * p : 0) +
                                   ((flags & kHasTransparency) ? 4 * p : 0) +
                                   ((flags & kHasColor) ? 12 * p : 0);
    if (expected != in.size())
        in.fail(4, "header counts (" + std::to_string(strands) + " strands, " +
                       std::to_string(points) + " points, flags " + std::to_string(flags) +
                       ") need " + std::to_string(expected) + " bytes, file has " +
                       std::to_string(in.size()));

    const std::size_t seg_at = kHeaderBytes;
    const std::size_t pts_at = seg_at + seg_bytes;
    const std::size_t thick_at = pts_at + 12 * p;

    // The segment counts must add up to the point count (64-bit sums: a
    // default of 2^32-1 segments must not wrap to 0 points per strand).
    const auto points_of = [&](std::uint32_t i) -> std::uint64_t {
        return 1 + std::uint64_t{(flags & kHasSegments) ? in.get<std::uint16_t>(seg_at + 2 * i)
                                                         : default_segments};
    };
    std::uint64_t total = 0;
    if (flags & kHasSegments) {
        for (std::uint32_t i = 0; i < strands; ++i) total += points_of(i);
    } else {
        total = s * (1 + std::uint64_t{default_segments});  // < 2^65 / 2: no wrap
    }
    if (total != points)
        in.fail(flags & kHasSegments ? seg_at : 16,
                "strand segment counts give " + std::to_string(total) + " points, header says " +
                    std::to_string(points));
    // Every strand has at least one point, so points >= strands and both are
    // bounded by the file size (checked above) before anything is reserved.

    LoadedCurves out;
    out.has_radius = true;
    out.strands.points.reserve(points);
    out.strands.radii.reserve(points);
    out.strands.offsets.reserve(std::size_t{strands} + 1);
    StrandBuilder build(out.strands, file.string());
    std::size_t k = 0;
    for (std::uint32_t i = 0; i < strands; ++i) {
        const std::uint64_t n = points_of(i);
        for (std::uint64_t j = 0; j < n; ++j, ++k) {
            const std::size_t at = pts_at + 12 * k;
            const Vec3 pos(in.get<float>(at), in.get<float>(at + 4), in.get<float>(at + 8));
            const float thickness =
                (flags & kHasThickness) ? in.get<float>(thick_at + 4 * k) : default_thickness;
            build.add_point(pos, 0.5f * thickness, at_byte(at));
        }
        build.end_strand(at_byte(flags & kHasSegments ? seg_at + 2 * i : pts_at + 12 * k));
    }
    return out;
}

}  // namespace rtc
