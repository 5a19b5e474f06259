// glTF pre-check (loaders/load_mesh.cpp): the structure assimp's glTF 2.0
// reader relies on without checking it, checked before assimp reads the file.
#pragma once

#include <filesystem>
#include <string>

namespace rtc {

// Throws InputError "<file>: ..." unless the file's JSON (a .gltf file, or a
// .glb file's JSON chunk, read alone) parses, and every mesh primitive has an
// `attributes` object whose POSITION names an accessor, integer `indices`
// naming an accessor if any, and a `mode` in 0..6 if any. assimp 5.2 crashes
// (SEGV) on a line-loop primitive with indices and no POSITION, found by the
// gltf fuzz harness. The node hierarchy must be trees (no node with two
// parents, no cycle) nested at most kMaxGltfNodeDepth levels: assimp walks
// it recursively (and load_mesh.cpp's own walk stops at 256 levels, after
// assimp). The error names the JSON key.
inline constexpr int kMaxGltfNodeDepth = 256;
void check_gltf_json(const std::filesystem::path& path, const std::string& file, bool binary);

}  // namespace rtc
