// Wavefront OBJ through tinyobjloader: faces fan-triangulated into a
// triangle mesh, `l` polylines into strands. tinyobjloader reads a malformed
// number as 0 without complaint, so the `v` lines are checked here first
// (strict numbers, finite), which also gives the line number in messages.
#include "scenes/file_bytes.h"
#include "scenes/loaders.h"
#include "scenes/strand_builder.h"
#include "scenes/text_lines.h"

#include <tiny_obj_loader.h>

#include <cmath>

namespace rtc {

namespace {

// Returns the number of vertices; throws on a bad `v` line.
std::size_t check_vertex_lines(const std::filesystem::path& file) {
    const std::vector<std::uint8_t> bytes = read_file_bytes(file);
    TextLines text(std::string(bytes.begin(), bytes.end()), file.string());
    std::size_t count = 0;
    while (text.next()) {
        if (text.blank() || text.tokens()[0] != "v") continue;
        if (text.tokens().size() < 4) text.fail("vertex needs 3 coordinates");
        for (std::size_t i = 1; i < 4; ++i) {
            const auto x = text.number<float>(i, "vertex coordinate");
            if (!std::isfinite(x)) text.fail("non-finite vertex coordinate");
        }
        ++count;
    }
    return count;
}

}  // namespace

ObjContents load_obj(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::size_t vertex_lines = check_vertex_lines(file);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    // No material directory: the geometry is all we need, and a missing .mtl
    // must not fail the load.
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, name.c_str(),
                                     nullptr, /*triangulate=*/false);
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        throw InputError(name + ": OBJ parse failed: " + err);
    }
    const std::size_t nv = attrib.vertices.size() / 3;
    if (nv != vertex_lines)
        throw InputError(name + ": OBJ reader found " + std::to_string(nv) + " vertices, file has " +
                         std::to_string(vertex_lines) + " `v` lines");

    ObjContents out;
    out.mesh.vertices.reserve(nv);
    for (std::size_t i = 0; i < nv; ++i)
        out.mesh.vertices.emplace_back(attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
                                       attrib.vertices[3 * i + 2]);
    auto vertex = [&](const tinyobj::index_t& idx, const char* what, std::size_t n) {
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= nv)
            throw InputError(name + ": " + what + " " + std::to_string(n) +
                             " refers to a vertex that does not exist (index " +
                             std::to_string(idx.vertex_index + 1) + " of " + std::to_string(nv) + ")");
        return static_cast<std::uint32_t>(idx.vertex_index);
    };

    std::size_t face_number = 0, line_number = 0;
    StrandBuilder build(out.lines, name);
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t k = 0;
        for (const unsigned char fv : shape.mesh.num_face_vertices) {
            ++face_number;
            if (fv < 3)
                throw InputError(name + ": face " + std::to_string(face_number) + " has " +
                                 std::to_string(fv) + " vertices");
            const std::uint32_t first = vertex(shape.mesh.indices[k], "face", face_number);
            for (unsigned j = 1; j + 1 < fv; ++j)
                out.mesh.triangles.push_back({first, vertex(shape.mesh.indices[k + j], "face", face_number),
                                              vertex(shape.mesh.indices[k + j + 1], "face", face_number)});
            k += fv;
        }
        std::size_t l = 0;
        for (const int lv : shape.lines.num_line_vertices) {
            ++line_number;
            for (int j = 0; j < lv; ++j, ++l) {
                const std::uint32_t v = vertex(shape.lines.indices[l], "polyline", line_number);
                build.add_point(out.mesh.vertices[v], 0.0f,
                                [&] { return "polyline " + std::to_string(line_number); });
            }
            build.end_strand([&] { return "polyline " + std::to_string(line_number); });
        }
    }
    return out;
}

}  // namespace rtc
