// libFuzzer harness: ray files and hit files (sim/ray_file.h) on arbitrary
// bytes, read whole and through the batched reader.
#include "fuzz_common.h"
#include "sim/workload/ray_file.h"

#include <array>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".bin");
    try {
        (void)rtc::read_ray_file(path);
    } catch (const rtc::InputError&) {
    }
    try {
        rtc::RayFileReader reader(path);
        std::array<rtc::Ray, 3> batch;
        while (reader.read(batch) > 0) {
        }
    } catch (const rtc::InputError&) {
    }
    try {
        (void)rtc::read_hit_file(path);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
