#pragma once

namespace rtc {
#ifdef RTCSIM_VERSION
inline constexpr const char* kVersion = RTCSIM_VERSION;
#else
inline constexpr const char* kVersion = "unknown";
#endif
}  // namespace rtc
