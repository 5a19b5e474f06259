// Memory of each method's acceleration structures, priced from a preset of
// bytes per node / instance / primitive box / triangle, plus the primitive
// data both methods share. Also the hardware's instance limit.
#pragma once

#include "intersectors/kinds.h"
#include "sim/hardware/presets/preset_file.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

struct MemoryModel {
    std::string name;
    PresetFiles files;  // as read by load_memory_model (null when parsed from text)
    std::string description;
    double node_bytes_w2 = 64, node_bytes_w4 = 128, node_bytes_w8 = 80;  // per inner node
    double custom_prim_bytes = 32;  // per custom-primitive AABB in a BLAS leaf
    double triangle_bytes = 48;     // per triangle in a BLAS (hardware format)
    double instance_bytes = 250;    // per TLAS instance
    double lss_prim_bytes = 32;     // per linear swept sphere in a BLAS (lss)
    double obb_child_bytes = 24;    // extra per child box with its own 3x4 transform (obb-nodes)
    double leaf_obb_bytes = 21;     // per primitive OBB read by a software leaf test (leaf-obb)
    double blas_bytes = 192;        // per BLAS: header and alignment padding of its buffer
    std::array<double, 4> primitive_data_bytes{32, 32, 32, 64};  // per PrimitiveKind
    double mesh_vertex_bytes = 12, mesh_triangle_bytes = 12;     // shared mesh data
    std::uint64_t instance_limit = 1u << 24;
    // True when instance_bytes is a measured whole (the instance structure's
    // size over its instance count), so the TLAS nodes are inside it.
    bool instance_includes_tlas_nodes = false;
    std::vector<std::pair<std::string, std::string>> sources;  // key -> provenance

    [[nodiscard]] double node_bytes(int width) const {
        return width == 2 ? node_bytes_w2 : width == 4 ? node_bytes_w4 : node_bytes_w8;
    }
};

// What a method's structures consist of (counted from the built structures or
// computed from the scene when the method is not built).
struct StructureCounts {
    std::uint64_t tlas_nodes = 0, blas_nodes = 0, instances = 0, custom_prims = 0, triangles = 0;
    std::uint64_t lss_prims = 0;          // hardware LSS primitives
    std::uint64_t oriented_children = 0;  // child boxes with their own transform
    std::uint64_t leaf_obbs = 0;          // per-primitive OBBs for a software leaf test
    // Triangles that stand in for curves (dots): their vertex and index
    // buffers, which the BLAS is built from and the method keeps. Their
    // BLAS records are counted in `triangles`.
    std::uint64_t strip_vertices = 0, strip_triangles = 0;
    std::uint64_t blases = 0;  // distinct BLASes (each has a header and an aligned buffer)
    int width = 4;
};

struct MemoryBreakdown {
    double tlas_nodes = 0, blas_nodes = 0, instances = 0, custom_prims = 0, triangles = 0;
    double lss_prims = 0, oriented_children = 0, leaf_obbs = 0;
    double blas_headers = 0;
    double strip_buffers = 0;  // dots: the stand-in triangles' vertices and indices
    double common = 0;  // primitive data + mesh, shared by every method
    // What the method builds and keeps (common is what every method shares).
    [[nodiscard]] double acceleration() const {
        return tlas_nodes + blas_nodes + instances + custom_prims + triangles + lss_prims +
               oriented_children + leaf_obbs + blas_headers + strip_buffers;
    }
    [[nodiscard]] double total() const { return acceleration() + common; }
};

[[nodiscard]] MemoryBreakdown price_memory(const StructureCounts& c, const MemoryModel& m,
                                           PrimitiveKind kind, std::uint64_t primitives,
                                           std::uint64_t mesh_vertices, std::uint64_t mesh_triangles);

// {"name", "description", "bytes": {"<key>": {"value", "source"}}, "instance_limit": {...}}
[[nodiscard]] MemoryModel load_memory_model(const std::string& path);
[[nodiscard]] MemoryModel parse_memory_model(const std::string& text, const std::string& file);

}  // namespace rtc
