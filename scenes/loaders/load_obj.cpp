// Wavefront OBJ through tinyobjloader: faces fan-triangulated into a
// triangle mesh, `l` polylines into strands. tinyobjloader reads a malformed
// number as 0 without complaint, converts out-of-range numbers to int (`vw`,
// indices) and follows `mtllib` to any path, so the text is checked here
// first and tinyobjloader only ever sees the statements the simulator uses,
// in a canonical form (see clean_obj). Errors name the file and line.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/generators/strand_builder.h"
#include "scenes/limits.h"
#include "scenes/loaders/text_lines.h"

#include <tiny_obj_loader.h>

#include <climits>
#include <cmath>
#include <sstream>

namespace rtc {

namespace {

struct CleanObj {
    std::string text;        // what tinyobjloader parses
    std::size_t vertices = 0;
};

// One face or polyline corner "v", "v/vt", "v//vn" or "v/vt/vn": the vertex
// index made absolute (1-based); negative indices count back from the last
// vertex so far. Texture and normal indices are dropped (never used).
long long corner_index(const TextLines& text, std::size_t i, std::size_t vertices_so_far) {
    const std::string_view tok = text.tokens()[i];
    const std::string_view head = tok.substr(0, tok.find('/'));
    long long v = 0;
    const char* first = head.data() + (head.size() > 1 && head[0] == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, head.data() + head.size(), v);
    if (ec != std::errc() || ptr != head.data() + head.size() || v == 0 || v > INT_MAX ||
        v < -static_cast<long long>(INT_MAX))
        text.fail("expected a vertex index (a non-zero integer), got \"" + std::string(tok) + "\"");
    if (v < 0) {
        v += static_cast<long long>(vertices_so_far) + 1;
        if (v < 1)
            text.fail("relative index " + std::string(head) + " reaches before the first vertex (" +
                      std::to_string(vertices_so_far) + " so far)");
    }
    return v;
}

// Checks every line and keeps `v x y z`, `f a b c ...` and `l a b ...` with
// absolute vertex indices; every other statement (normals, texture
// coordinates, `vw` skin weights once checked, groups, smoothing, materials:
// `mtllib` is never read) becomes an empty line, so line numbers still agree.
CleanObj clean_obj(const std::vector<std::uint8_t>& bytes, const std::string& file) {
    TextLines text(std::string(bytes.begin(), bytes.end()), file);
    CleanObj out;
    out.text.reserve(bytes.size());
    std::size_t faces = 0, polylines = 0;
    long long max_index = 0;
    std::size_t max_index_line = 0;
    std::string max_index_what;
    while (text.next()) {
        const auto& t = text.tokens();
        const std::string_view op = text.blank() ? std::string_view() : t[0];
        if (op == "v") {
            if (t.size() < 4) text.fail("vertex needs 3 coordinates");
            out.text += 'v';
            for (std::size_t i = 1; i < 4; ++i) {
                const auto x = text.number<float>(i, "vertex coordinate");
                if (!std::isfinite(x)) text.fail("non-finite vertex coordinate");
                if (std::abs(x) > kMaxCoordinate) text.fail(std::string("vertex coordinate beyond +-") + kMaxCoordinateText);
                out.text += ' ';
                out.text += t[i];
            }
            ++out.vertices;
        } else if (op == "vw") {
            // Skin weights "vw vertex (joint weight)...": never used, but a
            // malformed one is an error here as it was for tinyobjloader,
            // and an out-of-range joint must not reach its float-to-int cast.
            if (t.size() < 2 || t.size() % 2 != 0)
                text.fail("`vw` expects a vertex index and joint/weight pairs");
            const auto v = text.number<long long>(1, "skin weight vertex index");
            if (v < 0 || v > INT_MAX) text.fail("skin weight vertex index out of range");
            for (std::size_t i = 2; i < t.size(); i += 2) {
                const auto joint = text.number<double>(i, "joint id");
                const auto weight = text.number<double>(i + 1, "joint weight");
                if (!(joint >= 0.0 && joint <= INT_MAX) || !std::isfinite(weight))
                    text.fail("skin weight joint id must lie in [0, 2^31) and weight be finite, got \"" +
                              std::string(t[i]) + " " + std::string(t[i + 1]) + "\"");
            }
        } else if (op == "f" || op == "l") {
            const bool face = op == "f";
            const std::size_t number = face ? ++faces : ++polylines;
            const std::string what = (face ? "face " : "polyline ") + std::to_string(number);
            const std::size_t corners = t.size() - 1;
            if (face && corners < 3)
                text.fail(what + " has " + std::to_string(corners) + " vertices, need at least 3");
            if (face && corners > 255)  // tinyobjloader counts face corners in a byte
                text.fail(what + " has " + std::to_string(corners) + " vertices, at most 255 are supported");
            if (!face && corners < 2)
                text.fail(what + " has " + std::to_string(corners) + " point(s), need at least 2");
            out.text += op;
            for (std::size_t i = 1; i < t.size(); ++i) {
                const long long v = corner_index(text, i, out.vertices);
                if (v > max_index) {
                    max_index = v;
                    max_index_line = text.line_number();
                    max_index_what = what;
                }
                out.text += ' ';
                out.text += std::to_string(v);
            }
        }
        out.text += '\n';
    }
    if (max_index > static_cast<long long>(out.vertices))
        throw InputError(file + ": line " + std::to_string(max_index_line) + ": " + max_index_what +
                         " refers to vertex " + std::to_string(max_index) +
                         ", which does not exist (the file has " + std::to_string(out.vertices) +
                         " vertices)");
    return out;
}

}  // namespace

ObjContents load_obj(const std::filesystem::path& file) {
    const std::string name = file.string();
    const CleanObj clean = clean_obj(read_file_bytes(file), name);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    std::istringstream stream(clean.text);
    // No material reader: the geometry is all we need (and no `mtllib` line
    // reaches tinyobjloader anyway).
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream,
                                     /*readMatFn=*/nullptr, /*triangulate=*/false);
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
        throw InputError(name + ": OBJ parse failed: " + err);
    }
    const std::size_t nv = attrib.vertices.size() / 3;
    if (nv != clean.vertices)
        throw InputError(name + ": OBJ reader found " + std::to_string(nv) + " vertices, file has " +
                         std::to_string(clean.vertices) + " `v` lines");

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
            if (fv < 3 || k + fv > shape.mesh.indices.size())
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
            if (lv < 0 || l + static_cast<std::size_t>(lv) > shape.lines.indices.size())
                throw InputError(name + ": polyline " + std::to_string(line_number) + " is malformed");
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
