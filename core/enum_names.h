// Closed sets (events, primitive kinds, OBB variants, methods) are enums with a
// parallel table of names, because configs refer to them by string. One
// lookup serves every such table.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace rtc {

template <class Enum, std::size_t N>
[[nodiscard]] constexpr std::optional<Enum> enum_from_name(
    const std::array<std::string_view, N>& names, std::string_view name) {
    for (std::size_t i = 0; i < N; ++i)
        if (names[i] == name) return static_cast<Enum>(i);
    return std::nullopt;
}

}  // namespace rtc
