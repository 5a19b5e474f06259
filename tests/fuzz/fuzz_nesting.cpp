// libFuzzer harness: configs larger than libFuzzer's input size limit, made
// of repeated parts (deep nesting: the parser's depth limit, and the sweep
// expansion's recursive copy that once overflowed the stack at 100,000
// levels). The input's first two bytes give a repeat count K (0-262,140 in
// steps of 4); the rest is up to five lines: prefix, open, middle, close,
// suffix. The config text is prefix + open x K + middle + close x K + suffix
// (K cut so that the repeats stay within 8 MB),
// parsed and, when it is an object, run through the config pipeline.
#include "fuzz_pipeline.h"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return 0;
    const rtc::fuzz::RepeatedParts in = rtc::fuzz::repeated_parts(data, size, 5);
    const std::vector<std::string>& part = in.part;
    const std::size_t unit = part[1].size() + part[3].size();
    const std::size_t k = in.capped_for(unit);
    std::string text = part[0];
    text.reserve(part[0].size() + k * unit + part[2].size() + part[4].size());
    for (std::size_t i = 0; i < k; ++i) text += part[1];
    text += part[2];
    for (std::size_t i = 0; i < k; ++i) text += part[3];
    text += part[4];
    try {
        nlohmann::json config = rtc::parse_json_text(text, "fuzz.json");
        if (config.is_object()) rtc::fuzz::run_pipeline(std::move(config), {});
    } catch (const rtc::InputError&) {
    }
    return 0;
}
