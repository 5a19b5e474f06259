// libFuzzer harness: the txt curve loader on arbitrary bytes.
#include "fuzz_common.h"
#include "scenes/loaders/loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = rtc::fuzz::write_scratch(data, size, ".txt");
    try {
        (void)rtc::load_txt(path);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
