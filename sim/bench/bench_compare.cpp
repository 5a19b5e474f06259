#include "sim/bench/bench_compare.h"

#include "core/input_error.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <map>
#include <string>

namespace rtc {

namespace {

using nlohmann::json;

json read_json(const std::string& file) {
    std::ifstream in(file);
    if (!in) throw InputError("bench --compare: cannot read " + file);
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw InputError("bench --compare: " + file + ": not JSON: " + e.what());
    }
}

// "case/run/method" -> the method's object.
std::map<std::string, json> methods_of(const json& root, const std::string& file) {
    std::map<std::string, json> out;
    if (!root.is_object() || !root.contains("cases") || !root["cases"].is_array())
        throw InputError("bench --compare: " + file + ": /cases: missing (not a bench --json file)");
    for (const json& c : root["cases"]) {
        if (!c.contains("runs")) continue;  // skipped case
        for (const json& r : c.at("runs"))
            for (const json& m : r.at("methods"))
                out[std::to_string(c.at("id").get<int>()) + "/" + r.at("label").get<std::string>() +
                    "/" + m.at("method").get<std::string>()] = m;
    }
    return out;
}

// threads -> best rays/s (files before the thread list: the 1 and n figures).
std::map<unsigned, double> rates_of(const json& m) {
    std::map<unsigned, double> out;
    if (m.contains("rates")) {
        for (const json& t : m["rates"])
            out[t.at("threads").get<unsigned>()] = t.at("best_rays_per_second").get<double>();
    } else {
        if (m.value("rays_per_second_1_thread", 0.0) > 0.0)
            out[1] = m["rays_per_second_1_thread"].get<double>();
        out[m.value("threads", 0u)] = m.value("rays_per_second_all_threads", 0.0);
    }
    return out;
}

double ratio(double b, double a) { return a > 0.0 ? b / a : 0.0; }

}  // namespace

int compare_bench_json(const std::string& a_file, const std::string& b_file) {
    try {
        const json a_root = read_json(a_file), b_root = read_json(b_file);
        const auto a = methods_of(a_root, a_file), b = methods_of(b_root, b_file);
        std::printf("bench --compare: B / A, A = %s (load %.2f), B = %s (load %.2f)\n",
                    a_file.c_str(), a_root.value("load_average_start", -1.0), b_file.c_str(),
                    b_root.value("load_average_start", -1.0));
        std::printf("  %-22s %10s %10s %7s  %s\n", "case/run/method", "rays A", "rays B",
                    "build", "rays/s B/A per thread count (A, B Mrays/s)   events");
        bool all_same = true;
        int matched = 0;
        for (const auto& [key, ma] : a) {
            const auto it = b.find(key);
            if (it == b.end()) continue;
            const json& mb = it->second;
            ++matched;
            std::printf("  %-22s %10llu %10llu %6.2fx ", key.c_str(),
                        ma.value("rays", 0ull), mb.value("rays", 0ull),
                        ratio(mb.value("build_seconds", 0.0), ma.value("build_seconds", 0.0)));
            const auto ra = rates_of(ma), rb = rates_of(mb);
            for (const auto& [t, rate_a] : ra) {
                const auto rt = rb.find(t);
                if (rt == rb.end()) continue;
                std::printf(" %ut %.3fx (%.3f, %.3f)", t, ratio(rt->second, rate_a), rate_a * 1e-6,
                            rt->second * 1e-6);
            }
            const bool same = ma.value("events", json()) == mb.value("events", json()) &&
                              ma.value("rays", 0ull) == mb.value("rays", 0ull);
            all_same = all_same && same;
            std::printf("   %s\n", same ? "identical" : "EVENTS DIFFER");
        }
        for (const auto& [key, m] : a)
            if (!b.count(key)) std::printf("  %-22s only in A\n", key.c_str());
        for (const auto& [key, m] : b)
            if (!a.count(key)) std::printf("  %-22s only in B\n", key.c_str());
        std::printf("%d methods compared; event totals %s\n", matched,
                    all_same ? "identical" : "DIFFER");
        return all_same ? 0 : 1;
    } catch (const json::exception& e) {
        throw InputError("bench --compare: " + a_file + " / " + b_file + ": unexpected layout: " +
                         e.what());
    }
}

}  // namespace rtc
