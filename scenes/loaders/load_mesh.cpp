// Meshes by format: OBJ (tinyobjloader, load_obj.cpp), pbrt-v4 (pbrt/), and
// glTF 2.0 and PLY through assimp, which reads them well and is in Debian
// (libassimp-dev). assimp is lenient and allocates what a file declares, so
// the loader checks first: every file assimp opens (a glTF's buffers too)
// must be a regular file and all of them together at most `max_bytes`; a PLY
// header and ASCII body are checked line by line (ply_check.h). assimp's own
// errors become an InputError naming the file.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/gltf_check.h"
#include "scenes/loaders/loaders.h"
#include "scenes/loaders/ply_check.h"
#include "scenes/generators/strand_builder.h"
#include "scenes/limits.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <string_view>

namespace rtc {

namespace {

// The file system as assimp sees it, with the size and file-type checks.
class GuardedIO : public Assimp::DefaultIOSystem {
public:
    explicit GuardedIO(std::uint64_t max_bytes) : max_bytes_(max_bytes) {}
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        std::error_code ec;
        const std::filesystem::path p(file);
        if (std::string_view(mode).find_first_of("wa+") != std::string_view::npos) return refuse(p, "not opened for writing");
        if (!std::filesystem::is_regular_file(p, ec)) return refuse(p, "not a regular file (or missing)");
        const auto size = std::filesystem::file_size(p, ec);
        if (ec) return refuse(p, "cannot read its size");
        read_ += size;
        if (read_ > max_bytes_)
            return refuse(p, "the mesh and its buffers exceed " + std::to_string(max_bytes_) + " bytes");
        return Assimp::DefaultIOSystem::Open(file, mode);
    }
    [[nodiscard]] const std::string& refusal() const { return refusal_; }

private:
    Assimp::IOStream* refuse(const std::filesystem::path& p, const std::string& why) {
        if (refusal_.empty()) refusal_ = p.string() + ": " + why;
        return nullptr;
    }
    std::uint64_t max_bytes_;
    std::uint64_t read_ = 0;
    std::string refusal_;
};

void add_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, TriangleMesh& out,
              const std::string& file, int depth) {
    if (depth > 256) throw InputError(file + ": node hierarchy deeper than 256");
    const aiMatrix4x4 m = parent * node.mTransformation;
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
        if (node.mMeshes[i] >= scene.mNumMeshes) throw InputError(file + ": node refers to a missing mesh");
        const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
        if (out.vertices.size() + mesh.mNumVertices >= (std::size_t{1} << 31))
            throw InputError(file + ": more than 2^31 vertices (after node instancing)");
        const auto base = static_cast<std::uint32_t>(out.vertices.size());
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D p = m * mesh.mVertices[v];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || std::abs(p.x) > kMaxCoordinate ||
                std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate)
                throw InputError(file + ": mesh \"" + std::string(mesh.mName.C_Str()) + "\" vertex " + std::to_string(v) +
                                 " is not finite or lies beyond +-" + kMaxCoordinateText);
            out.vertices.emplace_back(p.x, p.y, p.z);
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices < 3) continue;  // points and lines: no surface
            for (unsigned k = 0; k < face.mNumIndices; ++k)
                if (face.mIndices[k] >= mesh.mNumVertices)
                    throw InputError(file + ": mesh \"" + std::string(mesh.mName.C_Str()) + "\" face " +
                                     std::to_string(f) + " refers to a missing vertex");
            // Fan triangulation (v0, vi, vi+1), as for OBJ faces.
            for (unsigned k = 1; k + 1 < face.mNumIndices; ++k)
                out.triangles.push_back({base + face.mIndices[0], base + face.mIndices[k], base + face.mIndices[k + 1]});
        }
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) add_node(scene, *node.mChildren[c], m, out, file, depth + 1);
}

// A .gltf file is a JSON object, a .glb file starts with the magic "glTF".
// Checked before assimp sees the file: when its glTF reader declines a file,
// assimp tries every other format's reader on it, and one of those (assimp
// 5.2) reads past the end of a short buffer (found by the fuzz harness on
// the 14 bytes `metrict''''{"a`). Reads only up to the first byte that is
// not a byte-order mark or JSON whitespace: assimp reads the whole file next.
void check_gltf_start(const std::filesystem::path& path, const std::string& file, bool binary) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file + ": cannot open file");
    if (binary) {
        char magic[4] = {};
        if (!in.read(magic, 4) || std::string_view(magic, 4) != "glTF")
            throw InputError(file + ": byte 0: a .glb file must start with \"glTF\"");
        return;
    }
    const auto fail = [&](std::size_t at) {
        throw InputError(file + ": byte " + std::to_string(at) + ": a .gltf file must be a JSON object (expected '{')");
    };
    std::size_t at = 0;
    int c = in.get();
    if (c == 0xEF) {  // a UTF-8 byte-order mark, or nothing a JSON text may start with
        if (in.get() != 0xBB || in.get() != 0xBF) fail(0);
        at = 3;
        c = in.get();
    }
    for (; c == ' ' || c == '\t' || c == '\n' || c == '\r'; ++at) c = in.get();
    if (c != '{') fail(at);
}

std::string lower_extension(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

TriangleMesh load_assimp_mesh(const std::filesystem::path& file, std::uint64_t max_bytes) {
    const std::string name = file.string();
    require_regular_file(file);
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) throw InputError(name + ": cannot open file");
    if (size > max_bytes)
        throw InputError(name + ": " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes) +
                         " a mesh may have");
    const std::string ext = lower_extension(file);
    if (ext == ".ply") check_ply(read_file_bytes(file), name);
    if (ext == ".gltf" || ext == ".glb") {
        check_gltf_start(file, name, ext == ".glb");
        check_gltf_json(file, name, ext == ".glb");
    }

    Assimp::Importer importer;
    auto* io = new GuardedIO(max_bytes);  // owned by the importer
    importer.SetIOHandler(io);
    // No post-processing: assimp 5.2's triangulation aborts (ai_assert) on
    // some malformed faces; polygons are fan-triangulated in add_node.
    const aiScene* scene = importer.ReadFile(name, 0);
    if (!scene || !scene->mRootNode) {
        std::string err = io->refusal().empty() ? importer.GetErrorString() : io->refusal();
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        throw InputError(name + ": cannot read the mesh: " + (err.empty() ? "unknown format" : err));
    }
    TriangleMesh out;
    add_node(*scene, *scene->mRootNode, aiMatrix4x4(), out, name, 0);
    return out;
}

std::optional<MeshFormat> mesh_format_from_name(std::string_view name) {
    if (name == "auto") return MeshFormat::Auto;
    if (name == "obj") return MeshFormat::Obj;
    if (name == "gltf" || name == "glb") return MeshFormat::Gltf;
    if (name == "ply") return MeshFormat::Ply;
    if (name == "pbrt") return MeshFormat::Pbrt;
    return std::nullopt;
}

TriangleMesh load_mesh(const std::filesystem::path& file, MeshFormat format, std::vector<std::string>* notes) {
    if (format == MeshFormat::Auto) {
        const std::string ext = lower_extension(file);
        const auto f = ext.empty() ? std::nullopt : mesh_format_from_name(ext.substr(1));
        if (!f || *f == MeshFormat::Auto)
            throw InputError(file.string() + ": cannot tell the mesh format from the extension \"" + ext +
                             "\" (use .obj .gltf .glb .ply .pbrt or name the format)");
        format = *f;
    }
    switch (format) {
        case MeshFormat::Obj: return load_obj(file).mesh;
        case MeshFormat::Gltf:
        case MeshFormat::Ply: return load_assimp_mesh(file);
        case MeshFormat::Pbrt: {
            PbrtScene pbrt = load_pbrt(file);
            if (notes) notes->insert(notes->end(), pbrt.notes.begin(), pbrt.notes.end());
            return std::move(pbrt.mesh);
        }
        case MeshFormat::Auto: break;
    }
    throw InputError(file.string() + ": unknown mesh format");
}

}  // namespace rtc
