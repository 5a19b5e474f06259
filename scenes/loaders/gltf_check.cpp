// glTF pre-check (see gltf_check.h); the layout as in the glTF 2.0
// specification (Khronos): a .glb is a 12-byte header, then chunks of
// (length, type, data), the first of type JSON.
#include "scenes/loaders/gltf_check.h"

#include "core/input_error.h"
#include "scenes/loaders/file_bytes.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>

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
