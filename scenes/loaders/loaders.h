// Loaders of the curve and mesh file formats (one .cpp per format). Every
// loader reads the whole file, checks it, and either returns the complete
// geometry or throws rtc::InputError naming the file and the byte offset or
// line of the first problem: never a partial load.
#pragma once

#include "scenes/scene.h"

#include <filesystem>
#include <optional>
#include <string_view>

namespace rtc {

// Curves as read from a file. Formats without a radius (TressFX, TrackVis,
// OBJ lines) give radius 0 and has_radius = false, so the scene description
// can insist on a radius being set rather than tracing invisible strands.
struct LoadedCurves {
    Strands strands;
    bool has_radius = false;
};

// Cem Yuksel HAIR: radius = thickness / 2 (per point, or the header default).
[[nodiscard]] LoadedCurves load_hair(const std::filesystem::path& file);
// TressFX 3 (float3 vertices) or 4 (float4 vertices), chosen by the version
// field; guide strands only (see follow_hairs.h to add follow hairs).
[[nodiscard]] LoadedCurves load_tfx(const std::filesystem::path& file);
// TrackVis .trk v2 streamlines, coordinates as stored (voxel-mm space).
[[nodiscard]] LoadedCurves load_trk(const std::filesystem::path& file);
// SWC neuron trees, decomposed into unbranched chains (one strand each) so
// that the segment count equals the number of parent-child pairs.
[[nodiscard]] LoadedCurves load_swc(const std::filesystem::path& file);
// Plain text curves: one "x y z r" line per point, a blank line between
// strands, '#' comments.
[[nodiscard]] LoadedCurves load_txt(const std::filesystem::path& file);

// OBJ via tinyobjloader: faces fan-triangulated into the mesh, `l` polylines
// into strands (radius 0).
struct ObjContents {
    TriangleMesh mesh;
    Strands lines;
};
[[nodiscard]] ObjContents load_obj(const std::filesystem::path& file);

enum class CurveFormat : std::uint8_t { Auto, Hair, Tfx, Trk, Swc, Obj, Txt };
[[nodiscard]] std::optional<CurveFormat> curve_format_from_name(std::string_view name);
// Auto picks by extension (.hair .tfx .trk .swc .obj .txt); an unknown
// extension is an InputError.
[[nodiscard]] LoadedCurves load_curves(const std::filesystem::path& file,
                                       CurveFormat format = CurveFormat::Auto);

}  // namespace rtc
