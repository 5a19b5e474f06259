// libFuzzer harness: PLY meshes (ASCII and binary) through the line-by-line
// pre-check and then assimp. assimp is a system library without coverage
// instrumentation, so the fuzzer steers by the pre-check's branches; what it
// must show is that no input the pre-check lets through crashes assimp.
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".ply");
    try {
        (void)rtc::load_assimp_mesh(path, std::uint64_t{1} << 24);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
