// TressFX binary hair (AMD): a fixed number of vertices per strand, positions
// at an offset given in the header. Version 3 stores float3 vertices (offset
// at byte 144 of a 296-byte header); version 4 stores float4 (x, y, z, w; w is
// the inverse mass, ignored here) with the offset at byte 12. Both may carry
// further arrays (tangents, thickness, UVs) after the positions, so the file
// must be at least, not exactly, as long as the positions need.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/generators/strand_builder.h"

#include <cmath>

namespace rtc {

LoadedCurves load_tfx(const std::filesystem::path& file) {
    const ByteReader in(read_file_bytes(file), file.string());
    in.require(0, 16, "TressFX header");
    const float version = in.get<float>(0);
    const bool v3 = version >= 3.0f && version < 4.0f;
    const bool v4 = version >= 4.0f && version < 5.0f;
    if (!v3 && !v4)
        in.fail(0, "bad version " + std::to_string(version) +
                       " (expected 3.x or 4.x; is this a TressFX binary file?)");
    const std::size_t header_bytes = v3 ? 296 : 160;
    in.require(0, header_bytes, "TressFX " + std::string(v3 ? "3" : "4") + " header");
    const auto strands = in.get<std::uint32_t>(4);
    const auto per_strand = in.get<std::uint32_t>(8);
    const std::size_t offset_field = v3 ? 144 : 12;
    const auto offset = in.get<std::uint32_t>(offset_field);
    const std::size_t stride = v3 ? 12 : 16;
    if (per_strand < 2)
        in.fail(8, "vertices per strand is " + std::to_string(per_strand) + ", need at least 2");
    if (offset < header_bytes)
        in.fail(offset_field, "vertex offset " + std::to_string(offset) + " lies inside the header");
    // strands x per_strand x stride can pass 2^64: compare the vertex count
    // against what the file can hold instead of multiplying out.
    const std::uint64_t vertices = std::uint64_t{strands} * per_strand;  // < 2^64
    in.require_records(offset, vertices, stride,
                       "header counts (" + std::to_string(strands) + " strands x " +
                           std::to_string(per_strand) + " vertices)",
                       4);

    LoadedCurves out;
    const std::size_t total = std::size_t{strands} * per_strand;
    out.strands.points.reserve(total);
    out.strands.radii.reserve(total);
    out.strands.offsets.reserve(std::size_t{strands} + 1);
    StrandBuilder build(out.strands, file.string());
    std::size_t at = offset;
    for (std::uint32_t i = 0; i < strands; ++i) {
        for (std::uint32_t j = 0; j < per_strand; ++j, at += stride)
            build.add_point(Vec3(in.get<float>(at), in.get<float>(at + 4), in.get<float>(at + 8)),
                            0.0f, at_byte(at));
        build.end_strand(at_byte(at));
    }
    return out;
}

}  // namespace rtc
