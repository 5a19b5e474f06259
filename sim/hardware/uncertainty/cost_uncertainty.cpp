#include "sim/hardware/uncertainty/cost_uncertainty.h"

#include "sim/hardware/cost_model.h"
#include "sim/util/json_reader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rtc {

namespace {

// splitmix64 (Steele, Lea and Flood 2014): a tiny generator whose output is
// fixed by its definition, unlike std::normal_distribution's.
class Normals {
public:
    explicit Normals(std::uint64_t seed) : state_(seed) {}
    double next() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        // Box-Muller on two uniforms in (0, 1): never log(0).
        const double u1 = uniform(), u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1)), t = 2.0 * std::numbers::pi * u2;
        spare_ = r * std::sin(t);
        has_spare_ = true;
        return r * std::cos(t);
    }

private:
    double uniform() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
    }
    std::uint64_t state_;
    double spare_ = 0.0;
    bool has_spare_ = false;
};

[[nodiscard]] double json_number(const JsonReader& r, const nlohmann::json& v, const std::string& key) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) r.fail(key, "expected a finite number, got " + describe(v));
    return v.get<double>();
}

}  // namespace

std::size_t CostUncertainty::free_count() const {
    return static_cast<std::size_t>(std::count_if(parameters.begin(), parameters.end(),
                                                  [](const UncertainParameter& p) { return p.free; }));
}

std::vector<std::vector<double>> psd_cholesky(const std::vector<std::vector<double>>& a) {
    const std::size_t n = a.size();
    double scale = 0.0;
    for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, std::abs(a[i][i]));
    // Round-off of a covariance computed from an eigen-decomposition: pivots
    // down to -tol count as zero (a direction without variance).
    const double tol = 1e-9 * std::max(scale, 1e-300);
    std::vector<std::vector<double>> l(n, std::vector<double>(n, 0.0));
    for (std::size_t j = 0; j < n; ++j) {
        double d = a[j][j];
        for (std::size_t k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
        if (d < -tol) throw std::invalid_argument(std::to_string(j) + "/" + std::to_string(j));
        const double root = d > tol ? std::sqrt(d) : 0.0;
        l[j][j] = root;
        for (std::size_t i = j + 1; i < n; ++i) {
            double s = a[i][j];
            for (std::size_t k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
            if (root > 0.0) {
                l[i][j] = s / root;
            } else if (std::abs(s) > 1e-6 * std::sqrt(std::abs(a[i][i] * a[j][j])) + tol) {
                throw std::invalid_argument(std::to_string(i) + "/" + std::to_string(j));  // PSD needs s = 0 here
            }
        }
    }
    return l;
}

CostUncertainty parse_cost_uncertainty(const JsonReader& r, const std::array<double, kEventCount>& cycles) {
    r.require_object();
    r.allow_only({"source", "parameters", "covariance", "fitted_on"});
    CostUncertainty u;
    u.source = r.string("source", "");
    const nlohmann::json* params = r.has("parameters") ? &r.json()["parameters"] : nullptr;
    if (!params || !params->is_array()) r.fail("parameters", "expected a list of fitted parameters");
    std::array<bool, kEventCount> seen{};
    for (std::size_t k = 0; k < params->size(); ++k) {
        const JsonReader p((*params)[k], r.file(), r.key_path("parameters/" + std::to_string(k)));
        p.require_object();
        p.allow_only({"events", "tie", "value", "min", "max", "free"});
        UncertainParameter q;
        const nlohmann::json& ev = p.json().contains("events") ? p.json()["events"] : nlohmann::json();
        // Empty: a fitted parameter none of whose events this preset takes
        // from the fit (a derived preset replaced them); it keeps its row.
        if (!ev.is_array()) p.fail("events", "expected a list of event names");
        for (std::size_t i = 0; i < ev.size(); ++i) {
            const auto e = ev[i].is_string() ? event_from_name(ev[i].get<std::string>()) : std::nullopt;
            const std::string key = "events/" + std::to_string(i);
            if (!e) p.fail(key, "unknown event " + describe(ev[i]) + " (see core/events.h)");
            if (seen[static_cast<std::size_t>(*e)]) p.fail(key, "event in more than one parameter");
            seen[static_cast<std::size_t>(*e)] = true;
            q.events.push_back(*e);
        }
        q.scale = p.choice("tie", "value", {"value", "scale"}) == "scale";
        q.lo = p.number("min", std::nullopt, 0.0, 1e9);
        q.hi = p.number("max", std::nullopt, q.lo, 1e9);
        q.value = p.number("value", std::nullopt, q.lo, q.hi);
        q.free = p.boolean("free", std::nullopt);
        if (q.free && !(q.value > 0.0)) p.fail("value", "a free parameter needs a positive value (its covariance is of the log)");
        for (Event e : q.events)
            if (!q.scale && std::abs(cycles[static_cast<std::size_t>(e)] - q.value) > 1e-9 * std::max(1.0, q.value))
                p.fail("value", "the preset prices " + std::string(event_name(e)) + " at " +
                                    describe(cycles[static_cast<std::size_t>(e)]) + ", not this value");
        u.parameters.push_back(std::move(q));
    }
    const std::size_t n = u.free_count();
    const nlohmann::json* cov = r.has("covariance") ? &r.json()["covariance"] : nullptr;
    if (!cov || !cov->is_array()) r.fail("covariance", "expected a list of rows (one per free parameter)");
    if (cov->size() != n)
        r.fail("covariance", std::to_string(cov->size()) + " rows for " + std::to_string(n) + " free parameters");
    for (std::size_t i = 0; i < n; ++i) {
        const nlohmann::json& row = (*cov)[i];
        const std::string key = "covariance/" + std::to_string(i);
        if (!row.is_array() || row.size() != n)
            r.fail(key, "expected a row of " + std::to_string(n) + " numbers, got " + describe(row));
        u.covariance.emplace_back();
        for (std::size_t j = 0; j < n; ++j) u.covariance[i].push_back(json_number(r, row[j], key + "/" + std::to_string(j)));
    }
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < i; ++j) {
            const double a = u.covariance[i][j], b = u.covariance[j][i];
            if (std::abs(a - b) > 1e-9 * std::max({std::abs(a), std::abs(b), 1e-300}))
                r.fail("covariance/" + std::to_string(i) + "/" + std::to_string(j),
                       "not symmetric: " + describe(a) + " against " + describe(b) + " at /" + std::to_string(j) + "/" + std::to_string(i));
        }
    try {
        (void)psd_cholesky(u.covariance);
    } catch (const std::invalid_argument& e) {
        r.fail("covariance/" + std::string(e.what()), "not positive semi-definite (a covariance must be)");
    }
    if (r.has("fitted_on")) u.fitted_on_json = r.child("fitted_on").json().dump();
    return u;
}

nlohmann::ordered_json cost_uncertainty_to_json(const CostUncertainty& u) {
    nlohmann::ordered_json j;
    j["source"] = u.source;
    j["parameters"] = nlohmann::ordered_json::array();
    for (const UncertainParameter& p : u.parameters) {
        nlohmann::ordered_json q;
        q["events"] = nlohmann::ordered_json::array();
        for (Event e : p.events) q["events"].push_back(std::string(event_name(e)));
        q["tie"] = p.scale ? "scale" : "value";
        q["value"] = p.value;
        q["min"] = p.lo;
        q["max"] = p.hi;
        q["free"] = p.free;
        j["parameters"].push_back(q);
    }
    j["covariance"] = u.covariance;
    // The preset's top-level fitted_on describes the workload; this one is
    // written only when a caller filled it.
    if (!u.fitted_on_json.empty()) j["fitted_on"] = nlohmann::ordered_json::parse(u.fitted_on_json);
    return j;
}

std::vector<CostModel> draw_cost_models(const CostModel& model, std::size_t n, std::uint64_t seed) {
    std::vector<CostModel> out;
    if (!model.uncertainty || n == 0) return out;
    const CostUncertainty& u = *model.uncertainty;
    const std::vector<std::vector<double>> l = psd_cholesky(u.covariance);
    const std::size_t m = l.size();
    Normals normals(seed);
    std::vector<double> g(m), z(m);
    out.reserve(n);
    // Whether the draw z puts every free parameter inside its bounds.
    const auto inside = [&] {
        std::size_t f = 0;
        for (const UncertainParameter& p : u.parameters) {
            if (!p.free) continue;
            const double v = p.value * std::exp(z[f++]);
            if (!(v >= p.lo && v <= p.hi)) return false;
        }
        return true;
    };
    for (std::size_t d = 0; d < n; ++d) {
        for (std::size_t attempt = 0;; ++attempt) {
            if (attempt == kMaxDrawAttempts)
                throw std::runtime_error("preset " + model.name + ": fewer than 1 in " +
                                         std::to_string(kMaxDrawAttempts) +
                                         " draws of its covariance fall inside the parameters' bounds");
            for (double& x : g) x = normals.next();
            for (std::size_t i = 0; i < m; ++i) {
                z[i] = 0.0;
                for (std::size_t k = 0; k <= i; ++k) z[i] += l[i][k] * g[k];
            }
            if (inside()) break;
        }
        CostModel c = model;
        c.uncertainty.reset();  // a draw is a plain model: nothing copies the block per draw
        std::size_t f = 0;
        for (const UncertainParameter& p : u.parameters) {
            if (!p.free) continue;
            const double v = p.value * std::exp(z[f++]);
            // Both ties: the events' costs move by the factor the value moves.
            for (Event e : p.events) c[e] = model[e] * (v / p.value);
        }
        c.settle();  // costs made of the drawn ones follow them
        out.push_back(std::move(c));
    }
    return out;
}

std::array<double, 2> interval_90(std::vector<double> s, double point) {
    if (s.empty()) return {point, point};
    std::sort(s.begin(), s.end());
    const auto at = [&s](double q) {
        const double h = q * static_cast<double>(s.size() - 1);
        const auto i = static_cast<std::size_t>(std::floor(h));
        return i + 1 < s.size() ? s[i] + (h - static_cast<double>(i)) * (s[i + 1] - s[i]) : s[i];
    };
    // The percentiles of the draws need not bracket the point estimate (the
    // clamping into the bounds and the non-linear speedup skew them): widen
    // to include it, so an interval never excludes the number it annotates.
    return {std::min(at(0.05), point), std::max(at(0.95), point)};
}

}  // namespace rtc
