#include "sim/util/paths.h"

#include "core/input_error.h"

#include <cctype>
#include <dlfcn.h>

#include <cstdlib>
#include <system_error>

namespace rtc {

namespace fs = std::filesystem;

std::string config_relative_path(const std::string& path, const std::string& config_file) {
    const fs::path p(path);
    if (path.empty() || p.is_absolute()) return path;
    return (fs::path(config_file).parent_path() / p).lexically_normal().string();
}

bool is_data_path(const std::string& path) { return path.rfind(kDataPrefix, 0) == 0; }

fs::path data_root() {
    if (const char* env = std::getenv("RTCSIM_DATA"); env && *env) return fs::path(env).lexically_normal();
#ifdef RTCSIM_SOURCE_DATA_DIR
    return RTCSIM_SOURCE_DATA_DIR;
#else
    return "data";
#endif
}

std::string config_data_path(const std::string& path, const std::string& config_file) {
    if (!is_data_path(path)) return config_relative_path(path, config_file);
    return (data_root() / path.substr(std::string(kDataPrefix).size())).lexically_normal().string();
}

std::vector<fs::path> preset_dirs() {
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv("RTCSIM_PRESET_DIR"); env && *env) dirs.emplace_back(env);
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec && !exe.empty()) dirs.push_back((exe.parent_path() / ".." / "share" / "rtcsim" / "hw").lexically_normal());
#ifdef RTCSIM_INSTALL_PRESET_DIR
    dirs.emplace_back(RTCSIM_INSTALL_PRESET_DIR);
#endif
#ifdef RTCSIM_SOURCE_PRESET_DIR
    dirs.emplace_back(RTCSIM_SOURCE_PRESET_DIR);
#endif
    // The file this function was loaded from: the program itself, or the
    // Python module, which a pip install puts beside its presets, wherever
    // the source tree went.
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&preset_dirs), &info) != 0 && info.dli_fname != nullptr) {
        const fs::path object = fs::path(info.dli_fname);
        if (object != exe && object.is_absolute()) dirs.push_back((object.parent_path() / "configs" / "hw").lexically_normal());
    }
    return dirs;
}

bool is_preset_name(const std::string& value) {
    const bool json = value.size() >= 5 && value.compare(value.size() - 5, 5, ".json") == 0;
    return !value.empty() && value.find('/') == std::string::npos && !json && value != "." && value != "..";
}

std::string resolve_preset(const std::string& value, const std::string& config_file, const std::string& key) {
    const std::string where = config_file + ": " + key + ": ";
    if (value.empty()) throw InputError(where + "expected a preset name such as \"turing-calibrated\" or a path");
    if (!is_preset_name(value)) {
        const std::string path = config_relative_path(value, config_file);
        std::error_code ec;
        if (!fs::exists(path, ec))  // the loader reports other problems (a directory...) itself
            throw InputError(where + "no such preset file: " + path + " (paths are relative to the config file)");
        return path;
    }
    std::string searched;
    for (const fs::path& dir : preset_dirs()) {
        const fs::path candidate = dir / (value + ".json");
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec)) return candidate.string();
        searched += (searched.empty() ? "" : ", ") + dir.string();
    }
    throw InputError(where + "no preset named \"" + value + "\" (searched " + searched +
                     "; set RTCSIM_PRESET_DIR or give a path ending in .json)");
}

bool in_preset_dir(const fs::path& file) {
    std::error_code ec;
    const fs::path target = fs::weakly_canonical(file, ec);
    if (ec) return false;
    for (const fs::path& dir : preset_dirs()) {
        const fs::path d = fs::weakly_canonical(dir, ec);
        if (ec || d.empty()) continue;
        if (target.parent_path() == d) return true;
    }
    return false;
}

std::string file_name_part(const std::string& name) {
    std::string s;
    for (const char c : name)
        s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' ? c : '_';
    return s;
}

}  // namespace rtc
