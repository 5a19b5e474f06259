// The real models in ../shared/data, which are not in the repository. A test
// that reads them first asks shared_present(path): when the data is absent it
// records a doctest MESSAGE naming the missing path and the test returns
// early, so a clone without ../shared still runs every other check and says
// what it could not run instead of failing.
#pragma once

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <initializer_list>

namespace rtc::test {

// RTCSIM_SHARED_DIR in the environment overrides the build's ../shared (to
// run the suite against another copy, or none).
inline std::filesystem::path shared_dir() {
    if (const char* env = std::getenv("RTCSIM_SHARED_DIR"); env && *env) return env;
    return RTCSIM_SHARED_DIR;
}
inline std::filesystem::path shared_data() { return shared_dir() / "data"; }

// True when every path exists; otherwise a MESSAGE names the first missing one.
inline bool shared_present(std::initializer_list<std::filesystem::path> paths) {
    for (const std::filesystem::path& p : paths) {
        if (!std::filesystem::exists(p)) {
            MESSAGE("skipped: " << p.string() << " is missing (real models from ../shared/data)");
            return false;
        }
    }
    return true;
}

}  // namespace rtc::test
