#include "sim/hardware/execution_model.h"

#include "sim/util/json_reader.h"

#include <algorithm>

namespace rtc {

const char* execution_name(ExecutionKind k) { return k == ExecutionKind::Warp ? "warp" : "per_ray"; }

void ExecutionModel::set_lockstep_events(std::vector<Event> events) {
    for (std::size_t e = 0; e < kEventCount; ++e) units_[e] = kEventUnits[e];
    for (const Event e : events) units_[static_cast<std::size_t>(e)] = EventUnit::Lockstep;
    lockstep_ = std::move(events);
}

ExecutionModel parse_execution_model(const JsonReader& r, const ExecutionModel& base) {
    r.allow_only({"model", "warp_width", "tile", "rt_parallel_lanes", "lockstep_events", "bvh_width",
                   "sm"});
    ExecutionModel m = base;
    const auto entry = [&](std::string_view key) {
        const JsonReader e = r.child(key);
        e.allow_only({"value", "source"});
        std::erase_if(m.sources, [&](const auto& s) { return s.first == key; });
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
    // Unset: every lane overlaps (the slowest lane bounds), unless a base
    // preset set it for the same warp width.
    const bool inherits_lanes = !base.sources.empty() && !r.has("warp_width");
    if (!r.has("rt_parallel_lanes") && !inherits_lanes) m.rt_parallel_lanes = m.warp_width;
    if (r.has("rt_parallel_lanes"))
        m.rt_parallel_lanes = entry("rt_parallel_lanes").number("value", std::nullopt, 1.0, m.warp_width);
    if (m.rt_parallel_lanes > m.warp_width)
        r.fail("rt_parallel_lanes", "more overlapping lanes than the warp has (" + std::to_string(m.warp_width) + ")");
    if (r.has("lockstep_events")) {
        const JsonReader e = entry("lockstep_events");
        const nlohmann::json& v = e.json()["value"];
        if (!v.is_array()) e.fail("value", "expected a list of RT-unit event names, got " + describe(v));
        std::vector<Event> loop;
        for (std::size_t i = 0; i < v.size(); ++i) {
            const auto ev = v[i].is_string() ? event_from_name(v[i].get<std::string>()) : std::nullopt;
            const std::string key = "value/" + std::to_string(i);
            if (!ev) e.fail(key, "unknown event " + describe(v[i]) + " (see core/events.h)");
            if (event_unit(*ev) != EventUnit::RtUnit)
                e.fail(key, std::string(event_name(*ev)) + " is not RT-unit work: only those can move into the shader's loop");
            if (std::find(loop.begin(), loop.end(), *ev) != loop.end())
                e.fail(key, std::string(event_name(*ev)) + " is listed twice");
            loop.push_back(*ev);
        }
        m.set_lockstep_events(std::move(loop));
    }
    if (r.has("bvh_width")) {
        const JsonReader e = entry("bvh_width");
        m.bvh_width = static_cast<int>(e.integer("value", std::nullopt, 2, 8));
        if (m.bvh_width != 2 && m.bvh_width != 4 && m.bvh_width != 8)
            e.fail("value", "expected 2, 4 or 8, got " + std::to_string(m.bvh_width));
    }
    if (r.has("sm")) {
        m.sm = parse_sm_model(r.child("sm"), base.sm);
        if (!m.warp()) r.fail("sm", "the SM model needs the warp model (\"model\": \"warp\")");
    }
    if (!m.lockstep_events().empty() && !m.warp())
        r.fail("lockstep_events", "lockstep events need the warp model (\"model\": \"warp\")");
    return m;
}

}  // namespace rtc
