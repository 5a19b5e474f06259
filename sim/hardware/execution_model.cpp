#include "sim/hardware/execution_model.h"

#include "sim/util/json_reader.h"

namespace rtc {

const char* execution_name(ExecutionKind k) { return k == ExecutionKind::Warp ? "warp" : "per_ray"; }

ExecutionModel parse_execution_model(const JsonReader& r) {
    r.allow_only({"model", "warp_width", "tile", "rt_parallel_lanes"});
    ExecutionModel m;
    const auto entry = [&](std::string_view key) {
        const JsonReader e = r.child(key);
        e.allow_only({"value", "source"});
        m.sources.emplace_back(std::string(key), e.string("source", std::nullopt));
        return e;
    };
    if (r.has("model")) {
        const JsonReader e = entry("model");
        m.kind = e.choice("value", std::nullopt, {"per_ray", "warp"}) == "warp" ? ExecutionKind::Warp
                                                                                : ExecutionKind::PerRay;
    }
    if (r.has("warp_width"))
        m.warp_width = static_cast<int>(entry("warp_width").integer("value", std::nullopt, 1, 64));
    if (r.has("tile")) {
        const JsonReader e = entry("tile");
        const nlohmann::json& v = e.json()["value"];
        if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer() ||
            v[0].get<long long>() < 1 || v[1].get<long long>() < 1 || v[0].get<long long>() > 64 ||
            v[1].get<long long>() > 64)
            e.fail("value", "expected [width, height] in pixels, each 1..64, got " + describe(v));
        m.tile_width = v[0].get<int>();
        m.tile_height = v[1].get<int>();
    }
    if (m.tile_width * m.tile_height != m.warp_width)
        r.fail("tile", "a tile of " + std::to_string(m.tile_width) + " x " + std::to_string(m.tile_height) +
                           " pixels does not fill a warp of " + std::to_string(m.warp_width) + " lanes");
    m.rt_parallel_lanes = m.warp_width;
    if (r.has("rt_parallel_lanes"))
        m.rt_parallel_lanes = entry("rt_parallel_lanes").number("value", std::nullopt, 1.0, m.warp_width);
    return m;
}

}  // namespace rtc
