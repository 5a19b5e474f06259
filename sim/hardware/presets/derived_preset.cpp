#include "sim/hardware/presets/derived_preset.h"

#include "core/input_error.h"
#include "sim/util/json_reader.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace rtc {

namespace {

// The derived presets being loaded on this thread, outermost first: a
// preset naming itself, directly or through others, would recurse forever.
thread_local std::vector<std::string> g_chain;
constexpr std::size_t kMaxDepth = 8;

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// Removes `e` from the fitted parameter that owns it: its cost no longer
// comes from the fit, so the fit's draws must not move it.
void leave_fit(CostModel& m, Event e) {
    if (!m.uncertainty) return;
    for (UncertainParameter& p : m.uncertainty->parameters) std::erase(p.events, e);
}

// A scaled event keeps its parameter; a "value" tie then no longer equals its
// cost, so the parameter is written as a factor (draws move events by the
// factor the parameter moves either way, cost_uncertainty.h).
void scaled_in_fit(CostModel& m, Event e) {
    if (!m.uncertainty) return;
    for (UncertainParameter& p : m.uncertainty->parameters)
        if (std::find(p.events.begin(), p.events.end(), e) != p.events.end()) p.scale = true;
}

}  // namespace

bool has_source_tag(const std::string& s) {
    for (const char* tag : {"[D]", "[M]", "[C]", "[I]"})
        if (s.find(tag) != std::string::npos) return true;
    return false;
}

CostModel parse_derived_preset(const JsonReader& r) {
    r.allow_only({"name", "description", "derived_from", "features", "hypothetical", "execution", "deltas"});
    const std::string base_name = r.string("derived_from", std::nullopt);
    if (base_name.empty() || std::filesystem::path(base_name).is_absolute())
        r.fail("derived_from", "expected a preset file beside this one, e.g. \"turing-calibrated.json\"");
    const std::filesystem::path here = std::filesystem::path(r.file()).parent_path();
    const std::string base_file = (here / base_name).string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(base_file, ec))
        r.fail("derived_from", "no preset file " + base_file + " (the base is named relative to this preset's folder)");
    const std::string here_file = std::filesystem::weakly_canonical(r.file(), ec).string();
    const std::string base_canonical = std::filesystem::weakly_canonical(base_file, ec).string();
    const auto seen = std::find(g_chain.begin(), g_chain.end(), base_canonical);
    if (seen != g_chain.end() || base_canonical == here_file) {
        std::string cycle;
        for (auto it = seen; it != g_chain.end(); ++it) cycle += std::filesystem::path(*it).filename().string() + " -> ";
        cycle += std::filesystem::path(here_file).filename().string() + " -> " +
                 std::filesystem::path(base_canonical).filename().string();
        r.fail("derived_from", "presets derive from each other in a cycle: " + cycle);
    }
    if (g_chain.size() >= kMaxDepth)
        r.fail("derived_from", "presets derive from each other more than " + std::to_string(kMaxDepth) + " deep");
    struct Depth {  // this preset is on the chain while its base loads, also when it throws
        explicit Depth(const std::string& file) { g_chain.push_back(file); }
        ~Depth() { g_chain.pop_back(); }
    };
    CostModel m = [&] {
        const Depth deeper(here_file);
        try {
            return load_cost_model(base_file);
        } catch (const InputError& e) {
            // The base's own error (file and key) names the derived preset
            // too: the config names only that one.
            if (g_chain.size() > 1) throw;  // an inner derived preset already said it
            throw InputError(std::string(e.what()) + " (the base of " + r.file() + ")");
        }
    }();

    m.derived_from = m.name;
    m.name = r.string("name", std::nullopt);
    m.description = r.string("description", "");
    for (std::size_t i = 0; i < kEventCount; ++i)
        if (m.prices(static_cast<Event>(i))) m.source[i] = m.derived_from + ": " + m.source[i];
    if (r.has("features")) m.features = parse_features(r);
    if (r.has("hypothetical")) parse_hypothetical(r.child("hypothetical"), m);
    if (r.has("execution")) m.execution = parse_execution_model(r.child("execution"), m.execution);

    const nlohmann::json* deltas = r.has("deltas") ? &r.json()["deltas"] : nullptr;
    if (!deltas || !deltas->is_array()) r.fail("deltas", "expected a list of deltas (an empty list for none)");
    std::vector<bool> changed(kEventCount, false);
    for (std::size_t k = 0; k < deltas->size(); ++k) {
        const JsonReader d((*deltas)[k], r.file(), r.key_path("deltas/" + std::to_string(k)));
        d.require_object();
        d.allow_only({"events", "scale", "value", "sum_of", "source"});
        const std::string source = d.string("source", std::nullopt);
        if (!has_source_tag(source))
            d.fail("source", "tag the source [D] documented, [M] measured, [C] read from code or [I] inferred");
        const int kinds = int(d.has("scale")) + int(d.has("value")) + int(d.has("sum_of"));
        if (kinds != 1) d.fail("", "give exactly one of \"scale\", \"value\" or \"sum_of\"");
        const nlohmann::json* ev = d.has("events") ? &d.json()["events"] : nullptr;
        if (!ev || !ev->is_array() || ev->empty()) d.fail("events", "expected a non-empty list of event names");
        for (std::size_t i = 0; i < ev->size(); ++i) {
            const std::string key = "events/" + std::to_string(i);
            const auto e = (*ev)[i].is_string() ? event_from_name((*ev)[i].get<std::string>()) : std::nullopt;
            if (!e) d.fail(key, "unknown event " + describe((*ev)[i]) + " (see core/events.h)");
            const auto idx = static_cast<std::size_t>(*e);
            if (!m.prices(*e)) d.fail(key, m.unpriced(*e));
            if (changed[idx]) d.fail(key, std::string(event_name(*e)) + " is changed by an earlier delta: merge the two");
            changed[idx] = true;
            const std::string was = m.derived_from + "'s " + number_text(m.cycles[idx]);
            if (d.has("scale")) {
                if (m.composition(*e))
                    d.fail(key, std::string(event_name(*e)) + " is a sum of other costs in " + m.derived_from +
                                    ": scale its terms, or replace it with \"value\" or \"sum_of\"");
                const double s = d.number("scale", std::nullopt, 0.0, 1e6);
                m.cycles[idx] *= s;
                m.source[idx] = source + " (x" + number_text(s) + " on " + was + ")";
                scaled_in_fit(m, *e);
                continue;
            }
            std::erase_if(m.composed, [&](const ComposedCost& c) { return c.target == *e; });
            leave_fit(m, *e);
            if (d.has("value")) {
                m.cycles[idx] = d.number("value", std::nullopt, 0.0, 1e9);
                m.source[idx] = source + " (was " + was + ")";
            } else {
                m.composed.push_back(parse_sum_of(d.child("sum_of"), *e, m));
                m.source[idx] = source;
            }
        }
    }
    if (!order_compositions(m.composed))
        r.fail("deltas", "sums of costs refer to each other in a cycle: " + composition_cycle(m.composed));
    m.settle();
    return m;
}

}  // namespace rtc
