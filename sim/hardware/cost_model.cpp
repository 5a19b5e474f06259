#include "sim/hardware/cost_model.h"

#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"


namespace rtc {

PricedRun price(const EventTotals& counts, const CostModel& model) {
    PricedRun out;
    for (std::size_t i = 0; i < kEventCount; ++i) {
        out.by_event[i] = static_cast<double>(counts.n[i]) * model.cycles[i];
        out.total_cycles += out.by_event[i];
    }
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
    r.allow_only({"name", "description", "cycles"});
    CostModel m;
    m.name = r.string("name", std::nullopt);
    m.description = r.string("description", "");
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
    return m;
}

CostModel load_cost_model(const std::string& path) {
    return parse_cost_model(read_text_file(path), path);
}

std::string cost_model_to_json(const CostModel& m) {
    nlohmann::ordered_json j;
    j["name"] = m.name;
    j["description"] = m.description;
    nlohmann::ordered_json cycles;
    for (std::size_t i = 0; i < kEventCount; ++i)
        cycles[std::string(kEventNames[i])] = {{"value", m.cycles[i]}, {"source", m.source[i]}};
    j["cycles"] = cycles;
    return j.dump(2) + "\n";
}

}  // namespace rtc
