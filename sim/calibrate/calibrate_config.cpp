// Parsing of the `calibrate` config block and matching of targets to runs
// (see calibrate_config.h, docs/calibration.md).
#include "sim/calibrate/calibrate_config.h"

#include "core/input_error.h"
#include "sim/util/paths.h"

#include <algorithm>
#include <cmath>

namespace rtc {
namespace {

// A reader of element `i` of array `key`, with path ".../key/i".
[[nodiscard]] JsonReader element(const JsonReader& r, std::string_view key, std::size_t i) {
    return {r.json().at(std::string(key)).at(i), r.file(), r.key_path(key) + "/" + std::to_string(i)};
}

[[nodiscard]] const nlohmann::json& array_of(const JsonReader& r, std::string_view key,
                                             const char* what) {
    if (!r.has(key)) r.fail(key, std::string("missing (expected a non-empty array of ") + what + ")");
    const nlohmann::json& a = r.json().at(std::string(key));
    if (!a.is_array() || a.empty())
        r.fail(key, std::string("expected a non-empty array of ") + what + ", got " + describe(a));
    return a;
}

[[nodiscard]] FitParameter parse_parameter(const JsonReader& p, std::vector<std::string>& seen) {
    p.allow_only({"events", "min", "max", "tie"});
    FitParameter f;
    const nlohmann::json& events = array_of(p, "events", "event names");
    for (std::size_t i = 0; i < events.size(); ++i) {
        const std::string at = p.key_path("events") + "/" + std::to_string(i);
        if (!events[i].is_string())
            throw InputError(p.file() + ": " + at + ": expected an event name, got " + describe(events[i]));
        const std::string name = events[i].get<std::string>();
        const std::optional<Event> e = event_from_name(name);
        if (!e) throw InputError(p.file() + ": " + at + ": unknown event \"" + name + "\" (see core/events.h)");
        for (const std::string& s : seen)
            if (s.substr(0, s.find(' ')) == name)
                throw InputError(p.file() + ": " + at + ": event \"" + name + "\" is already fitted at " +
                                 s.substr(s.find(' ') + 1) + " (an event may be in one parameter only)");
        seen.push_back(name + " " + at);
        f.events.push_back(*e);
    }
    f.lo = p.number("min", std::nullopt, 0.0, 1e9);
    f.hi = p.number("max", std::nullopt, 0.0, 1e9);
    if (f.hi < f.lo)
        p.fail("max", "must be >= min (" + describe(p.json().at("min")) + "), got " +
                          describe(p.json().at("max")));
    f.tie = p.choice("tie", "value", {"value", "scale"}) == "scale" ? Tie::Scale : Tie::Value;
    return f;
}

[[nodiscard]] CalibrationTarget parse_target(const JsonReader& t) {
    t.allow_only({"label", "match", "speedup", "weight"});
    CalibrationTarget out;
    out.where = t.file() + ": " + t.path();
    if (t.has("label") == t.has("match")) t.fail("", "needs exactly one of \"label\" or \"match\"");
    if (t.has("label")) {
        out.label = t.string("label", std::nullopt);
        if (out.label.empty()) t.fail("label", "must not be empty");
    } else {
        const nlohmann::json& m = t.json().at("match");
        if (!m.is_object() || m.empty())
            t.fail("match", "expected a non-empty object {\"sweep key\": value}, got " + describe(m));
        for (const auto& [key, value] : m.items())
            if (value.is_null() || value.is_object())
                t.fail("match", "value of \"" + key + "\" must be a number, string, bool or array, got " +
                                    describe(value));
        out.match = m;
    }
    out.speedup = t.positive("speedup", std::nullopt);
    out.weight = t.number("weight", 1.0, 0.0, 1e9);
    return out;
}

[[nodiscard]] bool same_value(const nlohmann::json& a, const nlohmann::json& b) {
    if (a.is_number() && b.is_number()) {
        const double x = a.get<double>(), y = b.get<double>();
        return x == y || std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y));
    }
    if (a.is_array() && b.is_array()) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (!same_value(a[i], b[i])) return false;
        return true;
    }
    return a == b;
}

[[nodiscard]] bool matches(const CalibrationTarget& t, const nlohmann::json& point,
                           std::string_view label) {
    if (!t.label.empty()) return !label.empty() && t.label == label;
    if (!point.is_object()) return false;
    for (const auto& [key, value] : t.match.items()) {
        const auto it = point.find(key);
        if (it == point.end() || !same_value(value, *it)) return false;
    }
    return true;
}

}  // namespace

CalibrateDesc parse_calibrate(const JsonReader& r) {
    r.allow_only({"parameters", "targets", "output", "name", "description", "reference",
                  "max_iterations", "start", "method"});
    CalibrateDesc d;
    std::vector<std::string> seen;
    const std::size_t np = array_of(r, "parameters", "parameters").size();
    for (std::size_t i = 0; i < np; ++i) d.parameters.push_back(parse_parameter(element(r, "parameters", i), seen));
    const std::size_t nt = array_of(r, "targets", "targets").size();
    for (std::size_t i = 0; i < nt; ++i) {
        CalibrationTarget t = parse_target(element(r, "targets", i));
        for (const CalibrationTarget& o : d.targets)
            if (o.label == t.label && same_value(o.match, t.match))
                throw InputError(t.where + ": same " + (t.label.empty() ? "match" : "label") +
                                 " as " + o.where.substr(o.where.rfind(": ") + 2));
        d.targets.push_back(std::move(t));
    }
    d.output = r.string("output", "");
    d.name = r.string("name", "");
    d.description = r.string("description", "");
    d.reference = r.string("reference", d.reference);
    d.start = r.string("start", "");
    d.method = r.string("method", d.method);
    d.max_iterations = static_cast<int>(r.integer("max_iterations", d.max_iterations, 1, 100000));
    return d;
}

CalibrationOptions calibration_options(const CalibrateDesc& d) {
    CalibrationOptions o;
    o.target_name = d.reference;
    o.name = d.name;
    o.description = d.description;
    o.max_iterations = d.max_iterations;
    return o;
}

const CalibrationTarget* find_target(const CalibrateDesc& d, const nlohmann::json& point,
                                     std::string_view label) {
    const CalibrationTarget* found = nullptr;
    for (const CalibrationTarget& t : d.targets) {
        if (!matches(t, point, label)) continue;
        if (found)
            throw InputError(t.where + ": ambiguous: this target and " + found->where +
                             " both match the run " + (label.empty() ? "" : "'" + std::string(label) + "' ") +
                             describe(point));
        found = &t;
    }
    return found;
}

std::optional<double> target_for(const CalibrateDesc& d, const nlohmann::json& point) {
    const CalibrationTarget* t = find_target(d, point);
    if (!t) return std::nullopt;
    return t->speedup;
}

std::vector<std::string> unmatched_targets(const CalibrateDesc& d,
                                           const std::vector<nlohmann::json>& points,
                                           const std::vector<std::string>& labels) {
    std::vector<std::string> out;
    for (const CalibrationTarget& t : d.targets) {
        bool hit = false;
        for (std::size_t i = 0; i < std::max(points.size(), labels.size()) && !hit; ++i)
            hit = matches(t, i < points.size() ? points[i] : nlohmann::json(),
                          i < labels.size() ? std::string_view(labels[i]) : std::string_view());
        if (!hit) out.push_back(t.where);
    }
    return out;
}

CalibratePlan plan_calibrate(const nlohmann::json& config, const std::string& file) {
    if (!config.is_object() || !config.contains("calibrate"))
        throw InputError(file + ": /calibrate: missing (simulate calibrate needs a calibrate block)");
    CalibratePlan plan;
    plan.file = file;
    plan.desc = parse_calibrate(JsonReader(config, file).child("calibrate"));
    // Loaded now, so refitting does not start from a file the fit's own
    // output may overwrite, nor from an edit made while the runs traced.
    if (!plan.desc.start.empty())
        plan.start = load_cost_model(resolve_preset(plan.desc.start, file, "/calibrate/start"));
    if (!plan.desc.output.empty()) plan.output = config_relative_path(plan.desc.output, file);
    return plan;
}

}  // namespace rtc
