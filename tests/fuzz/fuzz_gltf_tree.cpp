// libFuzzer harness: glTF node hierarchies (issue 56: a chain of 1,000,000
// nodes crashed assimp's recursive node walk). The input is a list of
// parent links: byte pairs (node, parent) over up to 4,096 nodes, after two
// bytes giving the length K of a chain (0-262,140 in steps of 4) put under
// node 0; each link adds the node to its parent's children, so inputs make
// trees, forests, shared children, self-links and cycles. Node 0 holds the
// mesh of tests/fixtures/gltf/quad.gltf (its buffer embedded). The file goes
// through the glTF pre-check and, when that accepts it, assimp.
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <string>
#include <vector>

// As fuzz_gltf: assimp 5.2 leaks on some malformed files, inside libassimp.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

namespace {

// The quad's accessors, views and buffer (two triangles), as in the fixture.
const char* const kQuad = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
 "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAABAAIAAAACAAMA"}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
               {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return 0;
    const std::size_t chain = 4 * (std::size_t(data[0]) | std::size_t(data[1]) << 8);
    constexpr std::size_t kLinked = 4096;
    std::size_t nodes = 1;
    for (std::size_t i = 2; i + 1 < size; i += 2)
        nodes = std::max({nodes, std::size_t(data[i]) % kLinked + 1, std::size_t(data[i + 1]) % kLinked + 1});
    std::vector<std::vector<std::size_t>> children(nodes + chain);
    for (std::size_t i = 2; i + 1 < size; i += 2)
        children[std::size_t(data[i + 1]) % kLinked].push_back(std::size_t(data[i]) % kLinked);
    for (std::size_t i = 0; i < chain; ++i)  // node 0 -> nodes -> nodes + 1 -> ...
        children[i == 0 ? 0 : nodes + i - 1].push_back(nodes + i);
    nlohmann::json gltf = nlohmann::json::parse(kQuad);
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t n = 0; n < children.size(); ++n) {
        nlohmann::json node = nlohmann::json::object();
        if (n == 0) node["mesh"] = 0;
        if (!children[n].empty()) node["children"] = children[n];
        list.push_back(std::move(node));
    }
    gltf["nodes"] = std::move(list);
    const std::string text = gltf.dump();
    const std::string path = rtc::fuzz::write_scratch(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(),
                                                      ".gltf");
    try {
        (void)rtc::load_assimp_mesh(path, std::uint64_t{1} << 24);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
