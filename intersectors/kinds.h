// The closed set of user-primitive kinds, and the OBB variants of the
// bounding programs (enums with a switch, not class hierarchies).
#pragma once

#include "core/enum_names.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace rtc {

enum class PrimitiveKind : std::uint8_t { Cylinder, Capsule, Link, Phantom };
inline constexpr std::array<std::string_view, 4> kPrimitiveKindNames = {"cylinder", "capsule",
                                                                        "link", "phantom"};

// Paper: the rule of Wald et al. 2020 (capsule/link: axis p0-p1 extended by the
// radius; curve: axis first-to-last control point, widened to cover).
// Tight: a tighter fit for curves (identical to Paper for straight kinds).
enum class ObbVariant : std::uint8_t { Paper, Tight };
inline constexpr std::array<std::string_view, 2> kObbVariantNames = {"paper", "tight"};

[[nodiscard]] constexpr std::string_view kind_name(PrimitiveKind k) {
    return kPrimitiveKindNames[static_cast<std::size_t>(k)];
}
[[nodiscard]] constexpr std::optional<PrimitiveKind> kind_from_name(std::string_view s) {
    return enum_from_name<PrimitiveKind>(kPrimitiveKindNames, s);
}
[[nodiscard]] constexpr std::string_view obb_variant_name(ObbVariant v) {
    return kObbVariantNames[static_cast<std::size_t>(v)];
}
[[nodiscard]] constexpr std::optional<ObbVariant> obb_variant_from_name(std::string_view s) {
    return enum_from_name<ObbVariant>(kObbVariantNames, s);
}

}  // namespace rtc
