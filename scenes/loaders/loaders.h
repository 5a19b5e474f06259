// Loaders of the curve and mesh file formats (one .cpp per format). Every
// loader reads the whole file, checks it, and either returns the complete
// geometry or throws rtc::InputError naming the file and the byte offset or
// line of the first problem: never a partial load.
#pragma once

#include "scenes/scene.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

// Curves as read from a file. Formats without a radius (TressFX, TrackVis,
// OBJ lines) give radius 0 and has_radius = false, so the scene description
// can insist on a radius being set rather than tracing invisible strands.
struct LoadedCurves {
    Strands strands;
    bool has_radius = false;
    std::vector<std::string> notes;  // what the file held and the scene drops (pbrt: PbrtScene::notes)
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

// pbrt-v4 scene files (scenes/loaders/pbrt/, docs/scenes.md): `curve` shapes
// become strands (radius = width / 2), `trianglemesh`, `bilinearmesh`,
// `loopsubdiv` (its control mesh) and `plymesh` become the mesh, every
// transform applied and object instances flattened. `Include` and `Import`
// resolve against the including file's folder, then the main file's (as
// pbrt-v4 does). Other directives are checked and skipped; so are sphere,
// disk and cylinder shapes, counted in `skipped_shapes`. What a run then
// does without (those shapes, the Camera, the Film's resolution: the
// config's workload sets camera and image) is said in `notes`, which a run
// prints as warnings and keeps in report.json (scene.notes). Errors name the
// file, line and token. The limits bound what a small file can make.
struct PbrtLimits {
    std::uint64_t max_elements = std::uint64_t{1} << 28;  // points + vertices + triangles, after instancing
    std::uint64_t max_bytes = std::uint64_t{1} << 32;     // read over the file and everything it includes
    std::size_t max_include_depth = 32;
};
struct PbrtScene {
    Strands curves;
    TriangleMesh mesh;
    std::size_t curve_shapes = 0;  // `curve` shapes loaded, instances counted once per use
    std::size_t mesh_shapes = 0;
    std::size_t files = 0;         // the main file plus every Include/Import
    std::map<std::string, std::size_t> skipped_shapes;
    std::string camera;                               // the Camera directive's type ("" without one)
    std::array<double, 2> film_resolution{0.0, 0.0};  // Film's x/yresolution (0: no Film)
    std::vector<std::string> notes;                   // "<file>: ..." per thing dropped, as above
};
// `basis`: what a curve's strand points are (pbrt/shapes.h): its cubic Bezier
// control points (Bezier, the default) or samples on the curve (BSpline).
[[nodiscard]] PbrtScene load_pbrt(const std::filesystem::path& file, const PbrtLimits& limits = {},
                                  CurveBasis basis = CurveBasis::Bezier);

// glTF 2.0 (.gltf with embedded or external buffers, .glb) and PLY (ASCII or
// binary) meshes through assimp: every triangle of every mesh node, node
// transforms applied; points and lines are dropped, polygons fan-triangulated.
// The file (and every buffer it names) must be under `max_bytes`; a PLY
// header is checked first (counts against the file size, errors by line).
[[nodiscard]] TriangleMesh load_assimp_mesh(const std::filesystem::path& file,
                                            std::uint64_t max_bytes = std::uint64_t{1} << 31);

enum class MeshFormat : std::uint8_t { Auto, Obj, Gltf, Ply, Pbrt };
[[nodiscard]] std::optional<MeshFormat> mesh_format_from_name(std::string_view name);
// Auto picks by extension (.obj .gltf .glb .ply .pbrt); the mesh part only
// (an OBJ's faces, a pbrt file's meshes). With `notes`, appends what the
// file held and the mesh drops (pbrt: PbrtScene::notes).
[[nodiscard]] TriangleMesh load_mesh(const std::filesystem::path& file, MeshFormat format = MeshFormat::Auto,
                                     std::vector<std::string>* notes = nullptr);

enum class CurveFormat : std::uint8_t { Auto, Hair, Tfx, Trk, Swc, Obj, Txt, Pbrt };
[[nodiscard]] std::optional<CurveFormat> curve_format_from_name(std::string_view name);
// `format`, or for Auto the format the extension names (.hair .tfx .trk .swc
// .obj .txt .pbrt); an unknown extension is an InputError.
[[nodiscard]] CurveFormat resolve_curve_format(const std::filesystem::path& file, CurveFormat format);
// The basis a format's curves have unless a config says otherwise: Bezier for
// pbrt (its curves are Bezier curves), BSpline for the polyline formats.
[[nodiscard]] CurveBasis default_curve_basis(CurveFormat resolved);
// Reads the file's strands with `basis` (default: the format's); for the
// polyline formats the basis only says how their points are read, for pbrt
// it also picks the points (load_pbrt).
[[nodiscard]] LoadedCurves load_curves(const std::filesystem::path& file,
                                       CurveFormat format = CurveFormat::Auto,
                                       std::optional<CurveBasis> basis = std::nullopt);

}  // namespace rtc
