// libFuzzer harness: a whole run config. Input starting with '{' is the
// config's JSON text; anything else is a list of `--set key.path=value`
// lines applied to a small base config (tests/configs/tiny.json's shape).
#include "fuzz_pipeline.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        if (!text.empty() && text[0] == '{') {
            rtc::fuzz::run_pipeline(rtc::parse_json_text(text, "fuzz.json"), {});
        } else {
            std::vector<std::string> sets;
            std::size_t at = 0;
            while (at <= text.size() && sets.size() < 16) {
                const std::size_t end = std::min(text.find('\n', at), text.size());
                if (end > at) sets.push_back(text.substr(at, end - at));
                at = end + 1;
            }
            rtc::fuzz::run_pipeline(rtc::parse_json_text(rtc::fuzz::kTinyConfig, "base.json"), sets);
        }
    } catch (const rtc::InputError&) {
    }
    return 0;
}
