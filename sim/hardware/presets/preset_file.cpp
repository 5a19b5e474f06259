#include "sim/hardware/presets/preset_file.h"

#include <filesystem>

namespace rtc {

PresetFiles prepend_preset_file(const std::string& path, std::string text, const PresetFiles& files) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    auto list = std::make_shared<std::vector<PresetFile>>();
    list->push_back({ec ? path : absolute.lexically_normal().string(), std::move(text)});
    if (files) list->insert(list->end(), files->begin(), files->end());
    return list;
}

}  // namespace rtc
