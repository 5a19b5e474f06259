// libFuzzer harness: the pbrt-v4 scene loader (tokenizer, parameter lists,
// directives, transforms, instances, curves and meshes) on arbitrary bytes,
// then the same file through load_curves and load_mesh. The limits are
// lowered so a small input cannot ask for gigabytes (instancing, includes).
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".pbrt");
    rtc::PbrtLimits limits;
    limits.max_elements = std::uint64_t{1} << 20;
    limits.max_bytes = std::uint64_t{1} << 24;
    limits.max_include_depth = 8;
    try {
        const rtc::PbrtScene scene = rtc::load_pbrt(path, limits);
        if (scene.curves.points.size() + scene.mesh.vertices.size() < 4096) {
            if (scene.curves.strand_count() > 0) (void)rtc::load_curves(path, rtc::CurveFormat::Pbrt);
            (void)rtc::load_mesh(path, rtc::MeshFormat::Pbrt);
        }
    } catch (const rtc::InputError&) {
    }
    return 0;
}
