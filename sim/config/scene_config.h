// The `scene` object of a simulate config: parsed into a SceneDesc (every
// key checked, data paths resolved to absolute paths and checked to exist)
// when the config is planned, and made into a Scene when a run starts.
// Three types:
//   {"type": "bundle", ...}  the paper's synthetic cylinder bundle
//   {"type": "hair", ...}    procedural hair/fur on a sphere or a mesh
//   {"type": "file", "curves": {...}, "mesh": {...}}  data files
// Every key, its default and its meaning is listed in docs/scenes.md.
// Unknown keys and bad values throw InputError naming the config file and
// the JSON path; a bad data file throws InputError naming that file.
#pragma once

#include "scenes/generators/bundle.h"
#include "scenes/generators/follow_hairs.h"
#include "scenes/generators/hair_gen.h"
#include "scenes/loaders/loaders.h"
#include "scenes/scene.h"
#include "sim/util/json_reader.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rtc {

enum class SceneType : std::uint8_t { Bundle, Hair, File };

// A data file named by a config.
struct DataPath {
    std::string key;              // its JSON path, e.g. "/scene/curves/path" (messages)
    std::filesystem::path path;   // absolute
    std::string shown;            // as resolved against the config file (scene names, messages)
};

// One curve file of a file scene.
struct CurveFileDesc {
    std::string key;              // the curve object's JSON path, e.g. "/scene/curves/0"
    DataPath path;
    CurveFormat format = CurveFormat::Auto;
    std::optional<float> radius;  // replaces the file's radii
    double radius_scale = 1.0;
    FollowHairDesc follow;        // per_guide 0: no follow hairs
};

struct MeshFileDesc {
    DataPath path;
    MeshFormat format = MeshFormat::Auto;
};

struct SceneDesc {
    std::string file;                  // the config file (messages)
    std::string key = "/scene";        // the block's JSON path
    SceneType type = SceneType::Bundle;
    std::optional<std::string> name;   // the block's "name"
    BundleDesc bundle;                 // type bundle
    HairDesc hair;                     // type hair
    std::optional<DataPath> hair_mesh; // type hair, emitter "mesh": the OBJ the hair grows on
    bool ribbons = false;              // type hair: the strands as ribbons of triangles (scenes/generators/ribbons.h)
    std::vector<CurveFileDesc> curves; // type file
    bool curve_list = false;           // "curves" is a list (the scene is named by its key)
    std::optional<MeshFileDesc> mesh;  // type file
    // "curve_basis" (every type), or its default: Bezier when every curve
    // file is pbrt (their curves are Bezier curves), else BSpline.
    CurveBasis curve_basis = CurveBasis::BSpline;
};

// Checks every key of the block `r` points at; touches no data file but to
// see that it exists.
[[nodiscard]] SceneDesc parse_scene(const JsonReader& scene_block);

// Generates or loads the scene. Throws InputError naming the data file, or
// the config file and key when a file's contents do not fit its keys (no
// strands, no radius, no faces).
[[nodiscard]] Scene load_scene(const SceneDesc& desc);

// parse_scene then load_scene (tests, the Python module, bench).
[[nodiscard]] Scene load_scene(const JsonReader& scene_block);


}  // namespace rtc
