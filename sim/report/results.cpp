// Tidy data over a run or a sweep: results.csv (one row per sweep point x
// method x cost preset, raw numbers), the sweep's combined report.json, and
// the human tables beside them (see report.h and docs/outputs.md).
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"
#include "sim/util/version.h"

#include <charconv>
#include <cmath>
#include <filesystem>

namespace rtc {

namespace {

// Shortest text that reads back as the same double; empty for NaN/inf.
std::string raw(double v) {
    if (!std::isfinite(v)) return "";
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc() ? std::string(buf, end) : "";
}

// A text cell that no CSV reader can split or take for a comment: no
// delimiter, quote, '#' or line break (numpy.genfromtxt does not read quotes).
std::string text(const std::string& s) {
    std::string out;
    for (const char c : s) {
        if (c == ',') out += ';';
        else if (c == '"') continue;
        else if (c == '#') out += "No.";
        else if (c == '\n' || c == '\r' || c == '\t') out += ' ';
        else out += c;
    }
    return out;
}

std::string cell(const nlohmann::json& v) {
    if (v.is_null()) return "";
    if (v.is_string()) return text(v.get<std::string>());
    if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
    if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
    if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
    if (v.is_number()) return raw(v.get<double>());
    return text(v.dump());
}

// Every leaf of a sweep value under its dotted path: {"scene": {"count": 1,
// "radius": 0.1}} gives "scene.count" and "scene.radius"; list items by index.
void flatten(const std::string& path, const nlohmann::json& v, std::vector<std::pair<std::string, nlohmann::json>>& out) {
    if (v.is_object() && !v.empty()) {
        for (const auto& [k, x] : v.items()) flatten(path + "." + k, x, out);
    } else if (v.is_array() && !v.empty() && !std::all_of(v.begin(), v.end(), [](const auto& x) { return x.is_primitive(); })) {
        for (std::size_t i = 0; i < v.size(); ++i) flatten(path + "." + std::to_string(i), v[i], out);
    } else if (v.is_array()) {
        std::string joined;
        for (const auto& x : v) {
            if (!joined.empty()) joined += ' ';
            joined += cell(x);
        }
        out.emplace_back(path, joined);
    } else {
        out.emplace_back(path, v);
    }
}

std::vector<std::pair<std::string, nlohmann::json>> flat_values(const RunResult& r) {
    std::vector<std::pair<std::string, nlohmann::json>> out;
    for (const auto& [k, v] : r.point.values.items()) flatten(k, v, out);
    return out;
}

std::string per(double a, std::uint64_t b) { return b ? raw(a / static_cast<double>(b)) : ""; }

}  // namespace

std::vector<std::string> sweep_columns(const std::vector<RunResult>& runs) {
    std::vector<std::string> columns;
    for (const RunResult& r : runs)
        for (const auto& [k, v] : flat_values(r))
            if (std::find(columns.begin(), columns.end(), k) == columns.end()) columns.push_back(k);
    return columns;
}

std::string results_csv(const std::vector<RunResult>& runs) {
    const std::vector<std::string> axes = sweep_columns(runs);
    std::vector<std::string> header{"run", "point"};
    header.insert(header.end(), axes.begin(), axes.end());
    for (const char* c : {"primitive_kind", "primitive_count", "aabb_over_obb_area", "method", "baseline", "cost_preset",
                          "execution", "memory_preset", "instances", "rays", "cycles", "cycles_per_ray", "speedup",
                          "speedup_low", "speedup_high", "sampling_low", "sampling_high", "is_calls", "is_calls_per_ray", "memory_bytes", "memory_mib", "memory_overhead_percent",
                          "hit_agreement", "reason"})
        header.emplace_back(c);
    std::vector<std::vector<std::string>> rows;
    for (std::size_t point = 0; point < runs.size(); ++point) {
        const RunResult& r = runs[point];
        std::vector<std::string> head{text(r.config.name), std::to_string(point)};
        const auto values = flat_values(r);
        for (const std::string& a : axes) {
            const auto it = std::find_if(values.begin(), values.end(), [&](const auto& kv) { return kv.first == a; });
            head.push_back(it == values.end() ? "" : cell(it->second));
        }
        head.push_back(std::string(kind_name(r.config.kind)));
        head.push_back(std::to_string(r.primitives));
        head.push_back(raw(r.areas.ratio_paper()));
        const MethodRun* base = r.baseline();
        for (const MethodRun& m : r.methods) {
            for (std::size_t p = 0; p < r.costs.size(); ++p) {
                std::vector<std::string> row = head;
                const CostModel& cost = r.costs[p];
                const std::uint64_t rays = m.runnable ? m.rays() : 0;
                const bool priced = m.runnable && p < m.priced.size() && m.priced[p].supported;
                const bool base_priced = base && base->runnable && p < base->priced.size() && base->priced[p].supported;
                const double speedup = m.method == r.config.baseline ? (priced ? 1.0 : NAN) : r.speedup(m.method, p);
                std::string reason;
                if (!m.runnable) reason = m.reason;
                else if (!priced) reason = "the preset's hardware has no " + m.priced[p].missing_feature;
                else if (!base_priced) reason = "the baseline " + r.config.baseline + " is n/a under this preset";
                else if (const std::string why = cost.hypothetical_reason(m.method); !why.empty())
                    reason = "hypothetical on this machine: " + why;
                const double mem = m.runnable ? m.memory.total() : NAN;
                const double overhead = m.method == r.config.baseline ? (m.runnable ? 0.0 : NAN)
                                                                      : r.memory_overhead_percent(m.method);
                const double cycles = priced ? m.priced[p].total_cycles : NAN;
                const double calls = m.runnable ? static_cast<double>(m.totals()[Event::IsCall]) : NAN;
                const auto interval = m.method == r.config.baseline ? std::nullopt : r.speedup_interval(m.method, p);
                const auto sampled = m.method == r.config.baseline ? std::nullopt : r.sampled_speedup(m.method, p);
                for (const std::string& c :
                     {text(m.method), text(r.config.baseline), text(cost.name),
                      std::string(cost.execution.warp() ? "warp" : "per_ray"), text(r.memory.name),
                      std::to_string(m.instances), m.runnable ? std::to_string(rays) : "", raw(cycles),
                      priced ? per(cycles, rays) : "", speedup > 0 ? raw(speedup) : "",
                      interval ? raw((*interval)[0]) : "", interval ? raw((*interval)[1]) : "",
                      sampled ? raw(sampled->interval[0]) : "", sampled ? raw(sampled->interval[1]) : "", raw(calls),
                      m.runnable ? per(calls, rays) : "", raw(mem), raw(mem / (1024.0 * 1024.0)), raw(overhead),
                      m.agreement ? raw(m.agreement->fraction()) : "", text(reason)})
                    row.push_back(c);
                rows.push_back(std::move(row));
            }
        }
    }
    // A column of whole numbers with an empty cell is written as 12.0, 7.0:
    // numpy.genfromtxt would read it as integers and fill the gap with -1.
    for (std::size_t c = 0; c < header.size(); ++c) {
        bool empty = false, whole = true;
        for (const auto& row : rows) {
            const std::string& v = row[c];
            empty = empty || v.empty();
            const std::size_t digits = v.find_first_not_of("0123456789", v.starts_with('-') ? 1 : 0);
            whole = whole && (v.empty() || (digits == std::string::npos && v != "-"));
        }
        if (empty && whole)
            for (auto& row : rows)
                if (!row[c].empty()) row[c] += ".0";
    }
    std::string csv;
    rows.insert(rows.begin(), header);
    for (const auto& row : rows) {
        for (std::size_t i = 0; i < row.size(); ++i) csv += (i ? "," : "") + row[i];
        csv += '\n';
    }
    return csv;
}

nlohmann::ordered_json sweep_report_json(const std::vector<RunResult>& runs,
                                         const std::vector<std::string>& point_dirs,
                                         const std::vector<nlohmann::ordered_json>* break_even) {
    nlohmann::ordered_json j;
    j["rtcsim_version"] = kVersion;
    j["name"] = runs.empty() ? "" : runs.front().config.name;
    nlohmann::ordered_json axes = nlohmann::ordered_json::array();
    for (const RunResult& r : runs)
        for (const auto& [k, v] : r.point.values.items())
            if (std::find(axes.begin(), axes.end(), k) == axes.end()) axes.push_back(k);
    j["axes"] = axes;
    j["points"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < runs.size(); ++i) {
        nlohmann::ordered_json p;
        p["index"] = i;
        p["label"] = runs[i].sweep_label;
        p["values"] = runs[i].point.values;
        p["dir"] = i < point_dirs.size() ? point_dirs[i] : "";
        // Each point's maps were computed once, when it finished: not again
        // for every later point (that made a sweep's maps quadratic).
        p["report"] = report_json(runs[i], break_even && i < break_even->size() ? &(*break_even)[i] : nullptr);
        j["points"].push_back(std::move(p));
    }
    return j;
}

void write_sweep_outputs(const std::vector<RunResult>& runs, const std::vector<std::string>& point_dirs,
                         const std::string& dir, const std::vector<nlohmann::ordered_json>* break_even) {
    const auto at = [&](const char* file) { return (std::filesystem::path(dir) / file).string(); };
    write_text_file(at("results.csv"), results_csv(runs));
    const Table t = summary_table(runs);
    write_text_file(at("summary.csv"), t.to_csv());
    write_text_file(at("summary.md"), t.to_markdown());
    const Table st = speedup_table(runs);
    write_text_file(at("speedups.csv"), st.to_csv());
    write_text_file(at("speedups.md"), st.to_markdown());
    // A sweep's points are in sub-directories; the top gets their reports in one file.
    const bool sweep = std::any_of(point_dirs.begin(), point_dirs.end(), [](const std::string& d) { return !d.empty(); });
    if (sweep) write_text_file(at("report.json"), sweep_report_json(runs, point_dirs, break_even).dump(2) + "\n");
}

}  // namespace rtc
