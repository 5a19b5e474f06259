// libFuzzer harness: `--set` arguments of any depth (issue 56: a key path of
// 60,000 levels or a value nested 65,500 deep overflowed the stack; the
// config files' 128-level limit did not cover them). Like fuzz_nesting, the
// input's first two bytes give a repeat count K (0-262,140 in steps of 4),
// the rest up to seven lines: a key prefix, a key level repeated K times
// (e.g. ".a"), a value prefix, an opening repeated K times, a middle, a
// closing repeated K times, a suffix. The spec key-prefix + level x K + "=" +
// value-prefix + opening x K + middle + closing x K + suffix (within 8 MB)
// goes through the sweep key order and the config pipeline on a small
// config, as the CLI, Python's sets= and a shard.json's sets take it.
#include "fuzz_pipeline.h"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return 0;
    const rtc::fuzz::RepeatedParts in = rtc::fuzz::repeated_parts(data, size, 7);
    const std::vector<std::string>& part = in.part;
    const std::size_t k = in.capped_for(part[1].size() + part[3].size() + part[5].size());
    std::string spec = part[0];
    for (std::size_t i = 0; i < k; ++i) spec += part[1];
    spec += "=" + part[2];
    for (std::size_t i = 0; i < k; ++i) spec += part[3];
    spec += part[4];
    for (std::size_t i = 0; i < k; ++i) spec += part[5];
    spec += part[6];
    try {
        const std::string text = rtc::fuzz::kTinyConfig;
        (void)rtc::sweep_key_order(text, {spec});
        rtc::fuzz::run_pipeline(rtc::parse_json_text(text, "fuzz.json"), {spec});
    } catch (const rtc::InputError&) {
    }
    return 0;
}
