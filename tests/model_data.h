// The real models (docs/data.md), which are not in the repository: they lie
// in the data root that "data:" paths name (rtc::data_root(): $RTCSIM_DATA,
// else the repository's data/, which scripts/fetch-data fills; scripts/test
// installs them from ../shared/data when that copy exists). A test that reads
// them first asks models_present(paths): when they are absent it records a
// doctest MESSAGE naming the missing path and the test returns early, so a
// clone without the models still runs every other check and says what it
// could not run instead of failing.
#pragma once

#include "sim/util/paths.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <initializer_list>

namespace rtc::test {

inline std::filesystem::path model_data() { return rtc::data_root(); }

// True when every path exists; otherwise a MESSAGE names the first missing one.
inline bool models_present(std::initializer_list<std::filesystem::path> paths) {
    for (const std::filesystem::path& p : paths) {
        if (!std::filesystem::exists(p)) {
            MESSAGE("skipped: " << p.string() << " is missing (install the real models with scripts/fetch-data)");
            return false;
        }
    }
    return true;
}

}  // namespace rtc::test
