// glTF pre-check (see gltf_check.h); the layout as in the glTF 2.0
// specification (Khronos): a .glb is a 12-byte header, then chunks of
// (length, type, data), the first of type JSON.
#include "scenes/loaders/gltf_check.h"

#include "core/input_error.h"
#include "scenes/loaders/file_bytes.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <vector>

namespace rtc {

namespace {

[[noreturn]] void fail_key(const std::string& file, const std::string& key, const std::string& problem) {
    throw InputError(file + ": JSON key " + key + ": " + problem);
}

// A .glb file's JSON chunk alone (its binary buffers are not read).
std::string read_glb_json(const std::filesystem::path& path, const std::string& file) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(file + ": cannot open file");
    std::uint32_t header[5] = {};  // magic, version, length; chunk 0's length and type
    if (!in.read(reinterpret_cast<char*>(header), sizeof header))
        throw InputError(file + ": byte 12: file truncated in the .glb header");
    if (header[4] != 0x4E4F534Au) throw InputError(file + ": byte 16: the first .glb chunk is not JSON");
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec || header[3] > size - sizeof header)
        throw InputError(file + ": byte 12: the JSON chunk's length " + std::to_string(header[3]) +
                         " runs past the end of the file");
    std::string text(header[3], '\0');
    if (!in.read(text.data(), static_cast<std::streamsize>(text.size())))
        throw InputError(file + ": byte 20: cannot read the JSON chunk");
    return text;
}

// An index into the top-level array `what`: a non-negative integer below its size.
void check_index(const nlohmann::json& v, const nlohmann::json& root, const char* what, const std::string& file,
                 const std::string& key) {
    const std::int64_t index = v.is_number_integer() ? v.get<std::int64_t>() : -1;
    if (index < 0) fail_key(file, key, "expected a non-negative integer");
    const auto it = root.find(what);
    const std::size_t n = it != root.end() && it->is_array() ? it->size() : 0;
    if (static_cast<std::uint64_t>(index) >= n)
        fail_key(file, key, "names " + std::string(what) + " " + std::to_string(index) + ", the file has " +
                                std::to_string(n));
}

// The node hierarchy: disjoint trees (glTF 2.0, 3.5.3), nested at most
// kMaxGltfNodeDepth levels. assimp walks it recursively, once per level, so
// a million-level chain overflowed its stack (SEGV) before the loader's own
// 256-level limit was reached, and a cycle never ends; modelling tools'
// hierarchies nest a few dozen levels.
void check_node_tree(const nlohmann::json& root, const std::string& file) {
    const auto nodes = root.find("nodes");
    if (nodes == root.end()) return;
    if (!nodes->is_array()) fail_key(file, "/nodes", "expected an array");
    const std::size_t n = nodes->size();
    std::vector<std::int64_t> parent(n, -1);
    for (std::size_t i = 0; i < n; ++i) {
        const nlohmann::json& node = (*nodes)[i];
        const std::string key = "/nodes/" + std::to_string(i);
        if (!node.is_object()) fail_key(file, key, "expected an object");
        const auto children = node.find("children");
        if (children == node.end()) continue;
        if (!children->is_array()) fail_key(file, key + "/children", "expected an array");
        for (std::size_t c = 0; c < children->size(); ++c) {
            const std::string child_key = key + "/children/" + std::to_string(c);
            check_index((*children)[c], root, "nodes", file, child_key);
            const auto child = (*children)[c].get<std::size_t>();
            if (child == i) fail_key(file, child_key, "a node cannot be its own child");
            if (parent[child] >= 0)
                fail_key(file, child_key, "node " + std::to_string(child) + " is already a child of node " +
                                              std::to_string(parent[child]) + " (the hierarchy must be trees)");
            parent[child] = static_cast<std::int64_t>(i);
        }
    }
    // Each node's depth by walking up to its root, remembered so every
    // parent link is followed once; a walk that never reaches a root is a cycle.
    std::vector<std::int64_t> depth(n, -1);
    std::vector<std::size_t> path;
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t at = i;
        path.clear();
        while (depth[at] < 0 && parent[at] >= 0 && path.size() <= n) {
            path.push_back(at);
            at = static_cast<std::size_t>(parent[at]);
        }
        if (path.size() > n) fail_key(file, "/nodes/" + std::to_string(i) + "/children", "the hierarchy has a cycle");
        if (depth[at] < 0) depth[at] = 1;  // a root
        for (auto it = path.rbegin(); it != path.rend(); ++it) {
            depth[*it] = depth[static_cast<std::size_t>(parent[*it])] + 1;
            if (depth[*it] > kMaxGltfNodeDepth)
                fail_key(file, "/nodes/" + std::to_string(parent[*it]) + "/children",
                         "node hierarchy nested deeper than " + std::to_string(kMaxGltfNodeDepth) + " levels");
        }
    }
}

}  // namespace

void check_gltf_json(const std::filesystem::path& path, const std::string& file, bool binary) {
    nlohmann::json root;
    try {
        // A .gltf file's JSON is the whole file.
        root = binary ? nlohmann::json::parse(read_glb_json(path, file)) : nlohmann::json::parse(read_file_bytes(path));
    } catch (const nlohmann::json::parse_error& e) {
        throw InputError(file + ": byte " + std::to_string(e.byte + (binary ? 20 : 0)) + ": invalid JSON");
    } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double (found by fuzz_gltf)
        throw InputError(file + ": invalid JSON: " + e.what());
    }
    if (!root.is_object()) throw InputError(file + ": the glTF JSON is not an object");
    check_node_tree(root, file);
    const auto meshes = root.find("meshes");
    if (meshes == root.end()) return;
    if (!meshes->is_array()) fail_key(file, "/meshes", "expected an array");
    for (std::size_t m = 0; m < meshes->size(); ++m) {
        const std::string mesh_key = "/meshes/" + std::to_string(m);
        const nlohmann::json& mesh = (*meshes)[m];
        if (!mesh.is_object()) fail_key(file, mesh_key, "expected an object");
        const auto prims = mesh.find("primitives");
        if (prims == mesh.end() || !prims->is_array()) fail_key(file, mesh_key + "/primitives", "expected an array");
        for (std::size_t p = 0; p < prims->size(); ++p) {
            const std::string key = mesh_key + "/primitives/" + std::to_string(p);
            const nlohmann::json& prim = (*prims)[p];
            if (!prim.is_object()) fail_key(file, key, "expected an object");
            const auto attributes = prim.find("attributes");
            if (attributes == prim.end() || !attributes->is_object())
                fail_key(file, key + "/attributes", "expected an object");
            const auto position = attributes->find("POSITION");
            if (position == attributes->end()) fail_key(file, key + "/attributes/POSITION", "missing");
            check_index(*position, root, "accessors", file, key + "/attributes/POSITION");
            if (const auto indices = prim.find("indices"); indices != prim.end())
                check_index(*indices, root, "accessors", file, key + "/indices");
            if (const auto mode = prim.find("mode"); mode != prim.end())
                if (!mode->is_number_integer() || mode->get<std::int64_t>() < 0 || mode->get<std::int64_t>() > 6)
                    fail_key(file, key + "/mode", "expected an integer 0..6");
        }
    }
}

}  // namespace rtc
