// Config overrides and sweeps on raw JSON, before any typed parsing:
// - `--set key.path=value` sets a key by its dotted path (value parsed as
//   JSON when it is valid JSON, else taken as a string; an object replaces);
// - a `sweep` block maps dotted paths to lists; the run is repeated for the
//   cartesian product of the lists. A list of objects is merged into the
//   object at the path (so paired values such as count+radius form one axis).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtc {

// Applies "a.b.c=value"; throws InputError naming `origin` on a malformed spec.
// The key path's levels plus the value's own nesting must stay within
// kMaxJsonDepth, the limit on config files: a deeper value would overflow
// the stack when the config is copied (check_set_depth).
void apply_set(nlohmann::json& config, const std::string& spec, const std::string& origin);

// Throws InputError naming `origin` and the start of the key when `spec`
// would nest the config deeper than kMaxJsonDepth (its key path's levels plus
// its value's nesting); one pass over the text, nothing built.
void check_set_depth(const std::string& spec, const std::string& origin);

// Sets `value` at a dotted path; with `merge`, an object value is merged into
// an object already there (sweep axes pairing several keys) instead of
// replacing it (--set). A level that is a list is entered by an element's
// index ("sweep.scene.0.radius"); throws std::out_of_range when that part is
// not an index of the list.
void set_by_path(nlohmann::json& config, const std::string& dotted_path,
                 const nlohmann::json& value, bool merge = false);

struct SweepPoint {
    nlohmann::json config;   // the config with this point's values applied, no `sweep` block
    nlohmann::json values;   // {"<path>": value, ...} of this point (empty for a single run)
    std::string label;       // "scene.count=1000 scene.tilt_deg=45", or "" for a single run
};

// Expands the `sweep` block (if any) into points: the first key varies
// slowest. nlohmann::json keeps object keys sorted, so the keys' order in the
// text is passed as `key_order` (sweep_key_order); keys missing from it come
// after, alphabetically. Errors name `file` and the sweep key.
[[nodiscard]] std::vector<SweepPoint> expand_sweep(const nlohmann::json& config, const std::string& file,
                                                   const std::vector<std::string>& key_order = {});

// True when two (sweep-expanded) configs trace the same rays through the same
// structures: they differ at most in the pricing-only keys `cost` and
// `memory` (and `name`/`description`).
[[nodiscard]] bool same_trace(const nlohmann::json& a, const nlohmann::json& b);

// The sweep keys in the order they are written: in the config text, then as
// `--set` overrides change them (`--set sweep={...}` replaces the order,
// `--set sweep.key=[...]` appends a new key). Empty when the text is not
// valid JSON (parse_json_text reports that).
[[nodiscard]] std::vector<std::string> sweep_key_order(const std::string& config_text,
                                                       const std::vector<std::string>& sets = {});

}  // namespace rtc
