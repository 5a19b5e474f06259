// libFuzzer harness: cost and memory presets (configs/hw/*.json) as text.
#include "fuzz_common.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/memory_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        (void)rtc::parse_cost_model(text, "preset.json");
    } catch (const rtc::InputError&) {
    }
    try {
        (void)rtc::parse_memory_model(text, "preset.json");
    } catch (const rtc::InputError&) {
    }
    return 0;
}
