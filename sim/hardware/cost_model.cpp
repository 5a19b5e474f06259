#include "sim/hardware/cost_model.h"

#include "sim/hardware/presets/derived_preset.h"
#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>


namespace rtc {

bool CostModel::has_feature(std::string_view f) const {
    for (const std::string& x : features)
        if (x == f) return true;
    return false;
}

bool order_compositions(std::vector<ComposedCost>& composed) {
    // Kahn's order: a sum after the sums among its terms; a cycle is left over.
    std::vector<ComposedCost> done;
    while (!composed.empty()) {
        const auto ready = std::find_if(composed.begin(), composed.end(), [&](const ComposedCost& c) {
            return std::none_of(c.terms.begin(), c.terms.end(), [&](const auto& t) {
                return std::any_of(composed.begin(), composed.end(), [&](const ComposedCost& o) { return o.target == t.first; });
            });
        });
        if (ready == composed.end()) return false;
        done.push_back(std::move(*ready));
        composed.erase(ready);
    }
    composed = std::move(done);
    return true;
}

std::string composition_cycle(const std::vector<ComposedCost>& composed) {
    // Every sum left over has a term that is another one's target: following
    // such terms as many steps as there are sums ends inside a cycle.
    const auto next = [&](const ComposedCost& c) -> const ComposedCost* {
        for (const auto& [e, w] : c.terms)
            for (const ComposedCost& o : composed)
                if (o.target == e) return &o;
        return nullptr;
    };
    if (composed.empty()) return {};
    const ComposedCost* at = &composed.front();
    for (std::size_t i = 0; i < composed.size() && at; ++i) at = next(*at);
    if (!at) return std::string(event_name(composed.front().target));
    std::string text(event_name(at->target));
    for (const ComposedCost* c = next(*at); c; c = next(*c)) {
        text += " -> " + std::string(event_name(c->target));
        if (c == at || text.size() > 4096) break;
    }
    return text;
}

void CostModel::settle() {
    for (const ComposedCost& c : composed) {
        double v = 0.0;
        for (const auto& [e, w] : c.terms) v += w * (*this)[e];
        (*this)[c.target] = v;
    }
}

const ComposedCost* CostModel::composition(Event e) const {
    for (const ComposedCost& c : composed)
        if (c.target == e) return &c;
    return nullptr;
}

std::string CostModel::hypothetical_reason(std::string_view method) const {
    for (const auto& [m, why] : hypothetical)
        if (m == method) return why;
    return {};
}

void parse_hypothetical(const JsonReader& r, CostModel& m) {
    for (const auto& item : r.json().items()) {
        const std::string method = item.key();  // a plain name: clang 14 cannot capture a structured binding
        const nlohmann::json& why = item.value();
        if (!why.is_string() || why.get<std::string>().empty())
            r.fail(method, "expected why this method is hypothetical on this machine, with its source");
        std::erase_if(m.hypothetical, [&](const auto& h) { return h.first == method; });
        m.hypothetical.emplace_back(method, why.get<std::string>());
    }
}

std::vector<std::string> parse_features(const JsonReader& r) {
    const nlohmann::json& f = r.json()["features"];
    if (!f.is_array()) r.fail("features", "expected a list of hardware feature names");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < f.size(); ++i) {
        const std::string key = "features/" + std::to_string(i);
        if (!f[i].is_string()) r.fail(key, "expected a feature name, got " + describe(f[i]));
        const std::string name = f[i].get<std::string>();
        // A misspelt feature would make a method n/a with exit 0.
        if (std::find(std::begin(kHardwareFeatures), std::end(kHardwareFeatures), name) == std::end(kHardwareFeatures)) {
            std::string known;
            for (const char* k : kHardwareFeatures) known += (known.empty() ? "" : ", ") + std::string(k);
            r.fail(key, "unknown hardware feature " + describe(f[i]) + " (known: " + known + ")");
        }
        out.push_back(name);
    }
    return out;
}

bool CostModel::prices(Event e) const {
    if (is_operation_event(e)) return program_pricing == ProgramPricing::ByOperation;
    if (is_program_name_event(e)) return program_pricing == ProgramPricing::ByName;
    return true;
}

std::string CostModel::unpriced(Event e) const {
    return "preset \"" + name + "\" does not price " + std::string(event_name(e)) +
           (is_operation_event(e) ? " (it prices programs by name)" : " (it prices programs by operation class, op_*)");
}

std::string CostModel::missing_feature(const std::vector<std::string>& needs) const {
    for (const std::string& n : needs)
        if (!has_feature(n)) return n;
    return {};
}

std::string resolution_note(const CostModel& m, std::uint64_t pixels) {
    const std::uint64_t fitted = m.fitted_on.pixels();
    if (fitted == 0 || pixels == 0 || (pixels * 4 >= fitted && pixels <= fitted * 4)) return {};
    const double ratio = pixels > fitted ? double(pixels) / double(fitted) : double(fitted) / double(pixels);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", ratio);
    // A derived preset was not fitted itself: its costs start from its base's fit.
    const std::string who = m.derived_from.empty() ? m.name + " was fitted at "
                                                   : m.name + " (derived from " + m.derived_from +
                                                         ") takes its costs from a fit at ";
    return who + std::to_string(m.fitted_on.width) + " x " + std::to_string(m.fitted_on.height) +
           " = " + std::to_string(fitted) + " pixels; this run has " + std::to_string(pixels) + " pixels (" + buf + "x " +
           (pixels > fitted ? "more" : "fewer") +
           "): the warp model's answer depends on how much scene an 8 x 4 tile covers "
           "(docs/execution-model.md, Resolution)";
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

ComposedCost parse_sum_of(const JsonReader& r, Event target, const CostModel& m) {
    ComposedCost c{target, {}};
    if (r.json().empty()) r.fail("", "expected at least one {\"<event>\": weight} term");
    for (const auto& [key, value] : r.json().items()) {
        const auto e = event_from_name(key);
        if (!e) r.fail(key, "unknown event (see core/events.h)");
        if (*e == target) r.fail(key, "a cost cannot be a sum of itself");
        if (!m.prices(*e)) r.fail(key, m.unpriced(*e));
        c.terms.emplace_back(*e, r.number(key, std::nullopt, 0.0, 1e6));
    }
    return c;
}

CostModel parse_cost_model(const std::string& text, const std::string& file) {
    const nlohmann::json j = parse_json_text(text, file);
    const JsonReader r(j, file);
    if (j.is_object() && j.contains("derived_from")) return parse_derived_preset(r);
    r.allow_only({"name", "description", "features", "hypothetical", "execution", "fitted_on", "cycles", "uncertainty"});
    CostModel m;
    m.name = r.string("name", std::nullopt);
    m.description = r.string("description", "");
    if (r.has("features")) m.features = parse_features(r);
    if (r.has("hypothetical")) parse_hypothetical(r.child("hypothetical"), m);
    if (r.has("execution")) m.execution = parse_execution_model(r.child("execution"));
    if (r.has("fitted_on")) {
        const JsonReader f = r.child("fitted_on");
        f.allow_only({"width", "height", "spp", "bounces", "config"});
        m.fitted_on.width = static_cast<int>(f.number("width", std::nullopt, 1.0, 1e6));
        m.fitted_on.height = static_cast<int>(f.number("height", std::nullopt, 1.0, 1e6));
        m.fitted_on.spp = static_cast<std::uint32_t>(f.number("spp", std::nullopt, 1.0, 1e6));
        m.fitted_on.bounces = static_cast<std::uint32_t>(f.number("bounces", std::nullopt, 0.0, 1e6));
        m.fitted_on.config = f.string("config", "");
    }
    const JsonReader cycles = r.child("cycles");
    bool by_operation = false;
    for (const auto& [key, value] : cycles.json().items()) {
        const auto e = event_from_name(key);
        if (!e) cycles.fail(key, "unknown event (see core/events.h)");
        by_operation = by_operation || is_operation_event(*e);
    }
    m.program_pricing = by_operation ? ProgramPricing::ByOperation : ProgramPricing::ByName;
    for (std::size_t i = 0; i < kEventCount; ++i) {
        const std::string name(kEventNames[i]);
        if (!m.prices(static_cast<Event>(i))) {
            if (cycles.has(name))
                cycles.fail(name, "this preset prices programs by operation class (op_*), so it cannot also "
                                  "price the program event \"" + name + "\" by name: remove one of the two");
            m.source[i] = by_operation ? "not priced: programs are priced by the operations they execute (op_*)"
                                       : "not priced: this preset prices programs by name";
            continue;
        }
        if (!cycles.has(name))
            cycles.fail(name, is_operation_event(static_cast<Event>(i))
                                  ? "missing: a preset that prices operation classes needs every op_* cost"
                                  : "missing: every event needs a cost");
        const JsonReader e = cycles.child(name);
        e.allow_only({"value", "source", "sum_of"});
        m.source[i] = e.string("source", std::nullopt);
        if (e.has("sum_of")) {
            m.composed.push_back(parse_sum_of(e.child("sum_of"), static_cast<Event>(i), m));
        } else {
            m.cycles[i] = e.number("value", std::nullopt, 0.0, 1e9);
        }
    }
    if (!order_compositions(m.composed)) {
        const std::string cycle = composition_cycle(m.composed);
        cycles.fail(cycle.substr(0, cycle.find(' ')), "sums of costs refer to each other in a cycle: " + cycle);
    }
    m.settle();
    for (const ComposedCost& c : m.composed) {  // a written value must be the sum (cost_model_to_json writes it)
        const JsonReader e = cycles.child(kEventNames[static_cast<std::size_t>(c.target)]);
        if (!e.has("value")) continue;
        const double v = e.number("value", std::nullopt, 0.0, 1e9), sum = m[c.target];
        if (std::abs(v - sum) > 1e-9 * std::max(1.0, sum))
            e.fail("value", describe(v) + " is not the sum of its terms (" + describe(sum) + "): remove it, or fix the terms");
    }
    if (r.has("uncertainty")) m.uncertainty = parse_cost_uncertainty(r.child("uncertainty"), m.cycles);
    return m;
}

CostModel load_cost_model(const std::string& path) {
    std::string text = read_text_file(path);
    CostModel m = parse_cost_model(text, path);
    m.files = prepend_preset_file(path, std::move(text), m.files);  // a derived preset's bases follow it
    return m;
}

std::string cost_model_to_json(const CostModel& m) {
    nlohmann::ordered_json j;
    j["name"] = m.name;
    j["description"] = m.description;
    // A derived preset is written flattened (standalone); its base is named.
    if (!m.derived_from.empty()) j["description"] = m.description + " (derived from " + m.derived_from + ")";
    j["features"] = m.features;
    if (!m.hypothetical.empty()) {
        nlohmann::ordered_json h;
        for (const auto& [method, why] : m.hypothetical) h[method] = why;
        j["hypothetical"] = h;
    }
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
        if (!m.execution.lockstep_events().empty()) {
            nlohmann::ordered_json names = nlohmann::ordered_json::array();
            for (Event x : m.execution.lockstep_events()) names.push_back(std::string(event_name(x)));
            e["lockstep_events"] = {{"value", names}, {"source", source("lockstep_events")}};
        }
        if (m.execution.bvh_width > 0)
            e["bvh_width"] = {{"value", m.execution.bvh_width}, {"source", source("bvh_width")}};
        if (m.execution.sm.enabled) {
            // The SM block as loaded, so a written preset (a fit's output)
            // prices on the same SM as the preset it started from.
            const SmModel& sm = m.execution.sm;
            const auto sm_source = [&](const std::string& key) {
                for (const auto& [k, v] : sm.sources)
                    if (k == key) return v;
                return std::string("default");
            };
            nlohmann::ordered_json b, regs;
            for (const auto& [name, n] : sm.registers) regs[name] = n;
            b["registers_per_sm"] = {{"value", sm.registers_per_sm}, {"source", sm_source("registers_per_sm")}};
            b["max_warps"] = {{"value", sm.max_warps}, {"source", sm_source("max_warps")}};
            b["allocation_unit"] = {{"value", sm.allocation_unit}, {"source", sm_source("allocation_unit")}};
            b["partitions"] = {{"value", sm.partitions}, {"source", sm_source("partitions")}};
            b["registers"] = {{"value", regs}, {"source", sm_source("registers")}};
            b["latency_per_issue"] = {{"value", sm.latency_per_issue}, {"source", sm_source("latency_per_issue")}};
            b["rt_unit_lanes"] = {{"value", sm.rt_unit_lanes}, {"source", sm_source("rt_unit_lanes")}};
            e["sm"] = b;
        }
        j["execution"] = e;
    }
    if (m.fitted_on.pixels() > 0)
        j["fitted_on"] = {{"width", m.fitted_on.width}, {"height", m.fitted_on.height}, {"spp", m.fitted_on.spp},
                          {"bounces", m.fitted_on.bounces}, {"config", m.fitted_on.config}};
    nlohmann::ordered_json cycles;
    for (std::size_t i = 0; i < kEventCount; ++i) {
        if (!m.prices(static_cast<Event>(i))) continue;
        nlohmann::ordered_json entry = {{"value", m.cycles[i]}};
        if (const ComposedCost* c = m.composition(static_cast<Event>(i))) {
            nlohmann::ordered_json terms;
            for (const auto& [e, w] : c->terms) terms[std::string(event_name(e))] = w;
            entry["sum_of"] = terms;
        }
        entry["source"] = m.source[i];
        cycles[std::string(kEventNames[i])] = entry;
    }
    j["cycles"] = cycles;
    if (m.uncertainty) j["uncertainty"] = cost_uncertainty_to_json(*m.uncertainty);
    return j.dump(2) + "\n";
}

}  // namespace rtc
