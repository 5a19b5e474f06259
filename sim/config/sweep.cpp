#include "sim/config/sweep.h"

#include "core/input_error.h"
#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"

#include <algorithm>
#include <stdexcept>

namespace rtc {

namespace {

std::vector<std::string> split_path(const std::string& dotted) {
    std::vector<std::string> parts;
    std::string cur;
    for (const char c : dotted) {
        if (c == '.' || c == '/') {
            if (!cur.empty()) parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    if (!cur.empty()) parts.push_back(cur);
    return parts;
}

// The key as an error message shows it: a 100 KB path would swamp the line.
std::string shown_key(const std::string& key) {
    if (key.size() <= 60) return key;
    std::size_t cut = 57;
    while (cut > 0 && (static_cast<unsigned char>(key[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
    return key.substr(0, cut) + "... (" + std::to_string(key.size()) + " bytes)";
}

}  // namespace

void check_set_depth(const std::string& spec, const std::string& origin) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos) return;  // apply_set reports the missing value
    const std::string key = spec.substr(0, eq);
    const std::size_t levels = split_path(key).size();
    const int room = kMaxJsonDepth - static_cast<int>(std::min<std::size_t>(levels, kMaxJsonDepth));
    const int nesting = json_nesting(std::string_view(spec).substr(eq + 1), room + 1);
    if (levels > static_cast<std::size_t>(kMaxJsonDepth) || nesting > room)
        throw InputError(origin + ": --set " + shown_key(key) + ": " +
                         (levels > static_cast<std::size_t>(kMaxJsonDepth)
                              ? "key path of " + std::to_string(levels) + " levels"
                              : "key path and value") +
                         " nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
}

void set_by_path(nlohmann::json& config, const std::string& dotted_path,
                 const nlohmann::json& value, bool merge) {
    nlohmann::json* node = &config;
    for (const std::string& part : split_path(dotted_path)) {
        if (node->is_array()) {
            // A list is entered by an element's index; anything else would
            // silently replace the whole list with an object.
            const std::size_t n = node->size();
            const bool digits = !part.empty() && part.size() <= 9 &&
                                std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
            if (!digits || std::stoul(part) >= n)
                throw std::out_of_range("\"" + part + "\" is not an index of the list there (0 to " +
                                        std::to_string(n == 0 ? 0 : n - 1) + (n == 0 ? ", the list is empty)" : ")"));
            node = &(*node)[std::stoul(part)];
            continue;
        }
        if (!node->is_object()) *node = nlohmann::json::object();
        node = &(*node)[part];
    }
    if (merge && value.is_object() && node->is_object())
        node->merge_patch(value);
    else
        *node = value;
}

void apply_set(nlohmann::json& config, const std::string& spec, const std::string& origin) {
    // Keys and bare-word values end up in the echoed config and the reports,
    // which nlohmann can only write as UTF-8.
    try {
        (void)nlohmann::json(spec).dump();
    } catch (const nlohmann::json::exception&) {
        throw InputError(origin + ": --set: argument is not valid UTF-8");
    }
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(origin + ": --set " + shown_key(spec) + ": expected key.path=value");
    check_set_depth(spec, origin);
    const std::string key = spec.substr(0, eq), text = spec.substr(eq + 1);
    nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
    if (value.is_discarded()) value = text;  // a bare word is a string
    try {
        set_by_path(config, key, value);
    } catch (const std::out_of_range& e) {
        throw InputError(origin + ": --set " + shown_key(key) + ": " + e.what());
    }
}

std::vector<std::string> sweep_key_order(const std::string& config_text, const std::vector<std::string>& sets) {
    std::vector<std::string> order;
    const nlohmann::ordered_json text = nlohmann::ordered_json::parse(config_text, nullptr, false);
    if (text.is_object() && text.contains("sweep") && text["sweep"].is_object())
        for (const auto& [key, values] : text["sweep"].items()) order.push_back(key);
    for (const std::string& spec : sets) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos) continue;
        const std::vector<std::string> path = split_path(spec.substr(0, eq));
        if (path.empty() || path[0] != "sweep") continue;
        if (path.size() > static_cast<std::size_t>(kMaxJsonDepth) ||
            json_nesting(std::string_view(spec).substr(eq + 1)) > kMaxJsonDepth)
            continue;  // apply_set refuses it, naming the argument
        if (path.size() == 1) {
            order.clear();
            const nlohmann::ordered_json v = nlohmann::ordered_json::parse(spec.substr(eq + 1), nullptr, false);
            if (v.is_object())
                for (const auto& [key, values] : v.items()) order.push_back(key);
            continue;
        }
        const std::string& key = path[1];
        if (std::find(order.begin(), order.end(), key) == order.end()) order.push_back(key);
    }
    return order;
}

std::vector<SweepPoint> expand_sweep(const nlohmann::json& config, const std::string& file,
                                     const std::vector<std::string>& key_order) {
    nlohmann::json base = config;
    if (!base.is_object() || !base.contains("sweep")) return {{base, nlohmann::json::object(), ""}};
    const nlohmann::json sweep = base["sweep"];
    base.erase("sweep");
    const JsonReader r(sweep, file, "/sweep");
    r.require_object();
    std::vector<std::pair<std::string, nlohmann::json>> axes;
    for (const auto& [key, values] : sweep.items()) {
        if (!values.is_array() || values.empty())
            r.fail(key, "expected a non-empty list of values, got " + describe(values));
        // Each level of the key nests the config once more (set_by_path).
        if (split_path(key).size() > static_cast<std::size_t>(kMaxJsonDepth))
            throw InputError(file + ": /sweep/" + shown_key(key) + ": key path nested deeper than " +
                             std::to_string(kMaxJsonDepth) + " levels");
        axes.emplace_back(key, values);
    }
    // First key slowest, in the written order (std::stable_sort keeps the rest alphabetical).
    const auto rank = [&](const std::string& key) {
        return static_cast<std::size_t>(std::find(key_order.begin(), key_order.end(), key) - key_order.begin());
    };
    std::stable_sort(axes.begin(), axes.end(), [&](const auto& a, const auto& b) { return rank(a.first) < rank(b.first); });
    std::vector<SweepPoint> points;
    std::vector<std::size_t> index(axes.size(), 0);
    for (;;) {
        SweepPoint p{base, nlohmann::json::object(), ""};
        const auto add_label = [&](const std::string& k, const nlohmann::json& v) {
            p.label += (p.label.empty() ? "" : " ") + k + "=" + (v.is_string() ? v.get<std::string>() : v.dump());
        };
        for (std::size_t a = 0; a < axes.size(); ++a) {
            const std::string& axis = axes[a].first;
            const nlohmann::json& v = axes[a].second[index[a]];
            try {
                set_by_path(p.config, axis, v, /*merge=*/true);
            } catch (const std::out_of_range& e) {
                r.fail(axis, e.what());
            }
            if (!v.is_object()) {
                p.values[axis] = v;
                add_label(axis, v);
                continue;
            }
            // A paired axis: record each member; label it by its "name" if it
            // has one (a whole scene block would swamp the label), else by its
            // scalar members.
            for (const auto& [k, x] : v.items()) p.values[axis + "." + k] = x;
            if (v.contains("name") && v["name"].is_string()) {
                add_label(axis, v["name"]);
                continue;
            }
            for (const auto& [k, x] : v.items())
                if (x.is_primitive()) add_label(axis + "." + k, x);
        }
        points.push_back(std::move(p));
        std::size_t a = axes.size();
        while (a > 0) {
            --a;
            if (++index[a] < axes[a].second.size()) break;
            index[a] = 0;
            if (a == 0) return points;
        }
        if (axes.empty()) return points;
    }
}

bool same_trace(const nlohmann::json& a, const nlohmann::json& b) {
    if (!a.is_object() || !b.is_object()) return a == b;
    nlohmann::json x = a, y = b;
    for (const char* key : {"cost", "memory", "name", "description"}) {
        x.erase(key);
        y.erase(key);
    }
    return x == y;
}

}  // namespace rtc
