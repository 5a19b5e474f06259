// TrackVis .trk v2 streamlines (http://trackvis.org/docs/?subsect=fileformat):
// a 1000-byte header, then per streamline an int32 point count m, m points of
// (x, y, z, scalars...) float32, then the properties. n_count = 0 means
// "unknown": read to the end of the file. Otherwise the file must hold
// exactly n_count streamlines with nothing after them.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/generators/strand_builder.h"

namespace rtc {

LoadedCurves load_trk(const std::filesystem::path& file) {
    const ByteReader in(read_file_bytes(file), file.string());
    in.require(0, 1000, "TrackVis header");
    if (std::memcmp(in.data(0), "TRACK", 6) != 0) in.fail(0, "bad magic (expected \"TRACK\\0\")");
    const auto header_size = in.get<std::int32_t>(996);
    if (header_size != 1000)
        in.fail(996, "header size is " + std::to_string(header_size) +
                         " (expected 1000; big-endian files are not supported)");
    const auto version = in.get<std::int32_t>(992);
    if (version != 1 && version != 2)
        in.fail(992, "unsupported version " + std::to_string(version));
    const auto n_scalars = in.get<std::int16_t>(36);
    const auto n_properties = in.get<std::int16_t>(238);
    if (n_scalars < 0) in.fail(36, "negative n_scalars");
    if (n_properties < 0) in.fail(238, "negative n_properties");
    const auto n_count = in.get<std::int32_t>(988);
    if (n_count < 0) in.fail(988, "negative streamline count " + std::to_string(n_count));

    const std::size_t point_bytes = 4 * (3 + static_cast<std::size_t>(n_scalars));
    LoadedCurves out;
    StrandBuilder build(out.strands, file.string());
    std::size_t at = 1000;
    for (std::int64_t i = 0; n_count == 0 ? at < in.size() : i < n_count; ++i) {
        const auto m = in.get<std::int32_t>(at, "streamline point count");
        if (m < 0) in.fail(at, "negative point count " + std::to_string(m));
        const std::size_t body = static_cast<std::size_t>(m) * point_bytes + 4 * static_cast<std::size_t>(n_properties);
        in.require(at + 4, body, "streamline " + std::to_string(i) + " (" + std::to_string(m) + " points)");
        const std::size_t start = at;
        at += 4;
        for (std::int32_t j = 0; j < m; ++j, at += point_bytes)
            build.add_point(Vec3(in.get<float>(at), in.get<float>(at + 4), in.get<float>(at + 8)),
                            0.0f, at_byte(at));
        at += 4 * static_cast<std::size_t>(n_properties);
        build.end_strand(at_byte(start));
    }
    if (at != in.size())
        in.fail(at, std::to_string(in.size() - at) + " bytes after the last of the " +
                        std::to_string(n_count) + " streamlines the header announces");
    return out;
}

}  // namespace rtc
