#include "sim/hardware/cost_model.h"

#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"


namespace rtc {

bool CostModel::has_feature(std::string_view f) const {
    for (const std::string& x : features)
        if (x == f) return true;
    return false;
}

std::string CostModel::missing_feature(const std::vector<std::string>& needs) const {
    for (const std::string& n : needs)
        if (!has_feature(n)) return n;
    return {};
}

PricedRun price(const EventTotals& counts, const CostModel& model) {
    PricedRun out;
    for (std::size_t i = 0; i < kEventCount; ++i) {
        out.by_event[i] = static_cast<double>(counts.n[i]) * model.cycles[i];
        out.total_cycles += out.by_event[i];
    }
    out.per_ray_cycles = out.total_cycles;
    return out;
}

double price_cycles(const RayCounts& counts, const CostModel& model) {
    double total = 0.0;
    for (std::size_t i = 0; i < kEventCount; ++i)
        total += static_cast<double>(counts.n[i]) * model.cycles[i];
    return total;
}

CostModel parse_cost_model(const std::string& text, const std::string& file) {
    const nlohmann::json j = parse_json_text(text, file);
    const JsonReader r(j, file);
    r.allow_only({"name", "description", "features", "execution", "cycles", "uncertainty"});
    CostModel m;
    m.name = r.string("name", std::nullopt);
    m.description = r.string("description", "");
    if (r.has("features")) {
        const nlohmann::json& f = j["features"];
        if (!f.is_array()) r.fail("features", "expected a list of hardware feature names");
        m.features.clear();
        for (std::size_t i = 0; i < f.size(); ++i) {
            if (!f[i].is_string() || f[i].get<std::string>().empty())
                r.fail("features/" + std::to_string(i), "expected a feature name, got " + describe(f[i]));
            m.features.push_back(f[i].get<std::string>());
        }
    }
    if (r.has("execution")) m.execution = parse_execution_model(r.child("execution"));
    const JsonReader cycles = r.child("cycles");
    for (const auto& [key, value] : cycles.json().items())
        if (!event_from_name(key)) cycles.fail(key, "unknown event (see core/events.h)");
    for (std::size_t i = 0; i < kEventCount; ++i) {
        const std::string name(kEventNames[i]);
        if (!cycles.has(name)) cycles.fail(name, "missing: every event needs a cost");
        const JsonReader e = cycles.child(name);
        e.allow_only({"value", "source"});
        m.cycles[i] = e.number("value", std::nullopt, 0.0, 1e9);
        m.source[i] = e.string("source", std::nullopt);
    }
    if (r.has("uncertainty")) m.uncertainty = parse_cost_uncertainty(r.child("uncertainty"), m.cycles);
    return m;
}

CostModel load_cost_model(const std::string& path) {
    return parse_cost_model(read_text_file(path), path);
}

std::string cost_model_to_json(const CostModel& m) {
    nlohmann::ordered_json j;
    j["name"] = m.name;
    j["description"] = m.description;
    j["features"] = m.features;
    if (m.execution.warp() || !m.execution.sources.empty()) {
        nlohmann::ordered_json e;
        const auto source = [&](const std::string& key) {
            for (const auto& [k, v] : m.execution.sources)
                if (k == key) return v;
            return std::string("default");
        };
        e["model"] = {{"value", execution_name(m.execution.kind)}, {"source", source("model")}};
        e["warp_width"] = {{"value", m.execution.warp_width}, {"source", source("warp_width")}};
        e["tile"] = {{"value", {m.execution.tile_width, m.execution.tile_height}}, {"source", source("tile")}};
        e["rt_parallel_lanes"] = {{"value", m.execution.rt_parallel_lanes}, {"source", source("rt_parallel_lanes")}};
        j["execution"] = e;
    }
    nlohmann::ordered_json cycles;
    for (std::size_t i = 0; i < kEventCount; ++i)
        cycles[std::string(kEventNames[i])] = {{"value", m.cycles[i]}, {"source", m.source[i]}};
    j["cycles"] = cycles;
    if (m.uncertainty) j["uncertainty"] = cost_uncertainty_to_json(*m.uncertainty);
    return j.dump(2) + "\n";
}

}  // namespace rtc
