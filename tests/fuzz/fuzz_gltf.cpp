// libFuzzer harness: glTF 2.0 (.gltf JSON text) meshes through assimp, behind
// the loader's file and size checks. assimp is a system library without
// coverage instrumentation, so this mostly shows whether assimp's glTF reader
// survives malformed files (crash, abort, leak) in this configuration.
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

// assimp 5.2 leaks a buffer on some malformed glTF files (e.g. a broken data
// URI with an out-of-range accessor: 60 bytes allocated inside libassimp,
// found by this harness). The leak is assimp's, on an error path the
// simulator leaves by exiting; leaks allocated anywhere else still fail.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".gltf");
    try {
        (void)rtc::load_assimp_mesh(path, std::uint64_t{1} << 24);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
