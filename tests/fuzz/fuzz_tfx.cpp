// libFuzzer harness: the tfx curve loader on arbitrary bytes.
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".tfx");
    try {
        (void)rtc::load_tfx(path);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
