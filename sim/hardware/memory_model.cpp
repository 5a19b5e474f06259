#include "sim/hardware/memory_model.h"

#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"

namespace rtc {

MemoryBreakdown price_memory(const StructureCounts& c, const MemoryModel& m, PrimitiveKind kind,
                             std::uint64_t primitives, std::uint64_t mesh_vertices,
                             std::uint64_t mesh_triangles) {
    MemoryBreakdown b;
    const double node = m.node_bytes(c.width);
    b.tlas_nodes = m.instance_includes_tlas_nodes && c.instances > 0 ? 0.0 : static_cast<double>(c.tlas_nodes) * node;
    b.blas_nodes = static_cast<double>(c.blas_nodes) * node;
    b.instances = static_cast<double>(c.instances) * m.instance_bytes;
    b.custom_prims = static_cast<double>(c.custom_prims) * m.custom_prim_bytes;
    b.triangles = static_cast<double>(c.triangles) * m.triangle_bytes;
    b.lss_prims = static_cast<double>(c.lss_prims) * m.lss_prim_bytes;
    b.oriented_children = static_cast<double>(c.oriented_children) * m.obb_child_bytes;
    b.leaf_obbs = static_cast<double>(c.leaf_obbs) * m.leaf_obb_bytes;
    b.blas_headers = static_cast<double>(c.blases) * m.blas_bytes;
    // The stand-in triangles' buffers are laid out as a mesh's are.
    b.strip_buffers = static_cast<double>(c.strip_vertices) * m.mesh_vertex_bytes +
                      static_cast<double>(c.strip_triangles) * m.mesh_triangle_bytes;
    b.common = static_cast<double>(primitives) *
                   m.primitive_data_bytes[static_cast<std::size_t>(kind)] +
               static_cast<double>(mesh_vertices) * m.mesh_vertex_bytes +
               static_cast<double>(mesh_triangles) * m.mesh_triangle_bytes;
    return b;
}

MemoryModel parse_memory_model(const std::string& text, const std::string& file) {
    const nlohmann::json j = parse_json_text(text, file);
    const JsonReader r(j, file);
    r.allow_only({"name", "description", "bytes", "instance_limit", "instance_includes_tlas_nodes"});
    MemoryModel m;
    m.name = r.string("name", std::nullopt);
    m.description = r.string("description", "");
    const JsonReader bytes = r.child("bytes");
    bytes.allow_only({"node_w2", "node_w4", "node_w8", "custom_prim", "triangle", "instance", "blas",
                      "lss_prim", "obb_child", "leaf_obb", "cylinder_data", "capsule_data", "link_data", "phantom_data", "mesh_vertex",
                      "mesh_triangle"});
    const auto read = [&](const char* key, double& out) {
        const JsonReader e = bytes.child(key);
        e.allow_only({"value", "source"});
        out = e.number("value", std::nullopt, 0.0, 1e6);
        m.sources.emplace_back(key, e.string("source", std::nullopt));
    };
    read("node_w2", m.node_bytes_w2);
    read("node_w4", m.node_bytes_w4);
    read("node_w8", m.node_bytes_w8);
    read("custom_prim", m.custom_prim_bytes);
    read("triangle", m.triangle_bytes);
    read("instance", m.instance_bytes);
    read("lss_prim", m.lss_prim_bytes);
    read("obb_child", m.obb_child_bytes);
    read("leaf_obb", m.leaf_obb_bytes);
    read("blas", m.blas_bytes);
    read("cylinder_data", m.primitive_data_bytes[0]);
    read("capsule_data", m.primitive_data_bytes[1]);
    read("link_data", m.primitive_data_bytes[2]);
    read("phantom_data", m.primitive_data_bytes[3]);
    read("mesh_vertex", m.mesh_vertex_bytes);
    read("mesh_triangle", m.mesh_triangle_bytes);
    if (r.has("instance_includes_tlas_nodes")) {
        const JsonReader e = r.child("instance_includes_tlas_nodes");
        e.allow_only({"value", "source"});
        m.instance_includes_tlas_nodes = e.boolean("value", std::nullopt);
        m.sources.emplace_back("instance_includes_tlas_nodes", e.string("source", std::nullopt));
    }
    const JsonReader limit = r.child("instance_limit");
    limit.allow_only({"value", "source"});
    m.instance_limit =
        static_cast<std::uint64_t>(limit.integer("value", std::nullopt, 1, 1ll << 40));
    m.sources.emplace_back("instance_limit", limit.string("source", std::nullopt));
    return m;
}

MemoryModel load_memory_model(const std::string& path) {
    std::string text = read_text_file(path);
    MemoryModel m = parse_memory_model(text, path);
    m.files = prepend_preset_file(path, std::move(text), nullptr);
    return m;
}

}  // namespace rtc
