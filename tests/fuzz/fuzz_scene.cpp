// libFuzzer harness: the `scene` block of a config (bundle, hair, file
// scenes) as JSON text, inside a small config with an 8 x 8 primary workload.
#include "fuzz_pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        nlohmann::json config = {{"name", "scene"},
                                 {"methods", {"ref"}},
                                 {"workload", {{"type", "primary"}, {"width", 8}, {"height", 8}, {"spp", 1}}}};
        config["scene"] = rtc::parse_json_text(text, "scene.json");
        rtc::fuzz::run_pipeline(std::move(config), {});
    } catch (const rtc::InputError&) {
    }
    return 0;
}
