#pragma once

namespace rtc {
#ifdef RTCSIM_VERSION
inline constexpr const char* kVersion = RTCSIM_VERSION;
#else
inline constexpr const char* kVersion = "unknown";
#endif

// The git commit the build was configured from (`git rev-parse --short HEAD`
// at CMake configure time; "unknown" outside a git checkout), and whether the
// working tree had uncommitted changes then. Reconfigure to refresh.
[[nodiscard]] const char* git_commit();
[[nodiscard]] bool git_dirty();
}  // namespace rtc
