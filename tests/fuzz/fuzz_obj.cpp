// libFuzzer harness: the OBJ loader (mesh and polylines) on arbitrary bytes,
// and the OBJ-as-curves path of load_curves.
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".obj");
    try {
        const rtc::ObjContents obj = rtc::load_obj(path);
        if (obj.lines.strand_count() > 0) (void)rtc::load_curves(path, rtc::CurveFormat::Obj);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
