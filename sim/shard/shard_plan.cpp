#include "sim/shard/shard_plan.h"

#include "core/input_error.h"

#include <charconv>

namespace rtc {

namespace {

bool parse_u32(const std::string& s, std::uint32_t& v) {
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && p == s.data() + s.size() && !s.empty();
}

}  // namespace

ShardSpec parse_shard_spec(const std::string& text, const std::string& option) {
    const std::size_t slash = text.find('/');
    ShardSpec s;
    if (slash == std::string::npos || !parse_u32(text.substr(0, slash), s.index) ||
        !parse_u32(text.substr(slash + 1), s.count))
        throw InputError(option + ": expected I/N such as 0/4, got \"" + text + "\"");
    if (s.count == 0 || s.count > 100000)
        throw InputError(option + ": N must be 1 .. 100000, got " + std::to_string(s.count));
    if (s.index >= s.count)
        throw InputError(option + ": I must be 0 .. N - 1 = " + std::to_string(s.count - 1) + ", got " +
                         std::to_string(s.index));
    return s;
}

std::vector<ShardUnit> shard_units(std::size_t points, std::uint32_t shards) {
    std::vector<ShardUnit> units;
    if (shards == 0 || points == 0) return units;
    if (points >= shards) {
        for (std::size_t p = 0; p < points; ++p) units.push_back({p, 0, 1});
        return units;
    }
    const std::uint32_t per = shards / static_cast<std::uint32_t>(points);
    const std::uint32_t extra = shards % static_cast<std::uint32_t>(points);
    for (std::size_t p = 0; p < points; ++p) {
        const std::uint32_t bands = per + (p < extra ? 1u : 0u);
        for (std::uint32_t b = 0; b < bands; ++b) units.push_back({p, b, bands});
    }
    return units;
}

std::vector<ShardUnit> units_of_shard(std::size_t points, const ShardSpec& spec) {
    // Units index, index + count, ... of shard_units(), computed directly:
    // listing every unit for each shard made --estimate --shards N quadratic.
    std::vector<ShardUnit> mine;
    if (spec.count == 0 || points == 0) return mine;
    if (points >= spec.count) {
        for (std::size_t u = spec.index; u < points; u += spec.count) mine.push_back({u, 0, 1});
        return mine;
    }
    // Fewer points than shards: one unit per shard. The first `extra` points
    // have per + 1 bands, the others per.
    const auto n = static_cast<std::uint32_t>(points);
    const std::uint32_t per = spec.count / n, extra = spec.count % n;
    const std::uint64_t in_longer = std::uint64_t{extra} * (per + 1);
    if (spec.index < in_longer) {
        mine.push_back({spec.index / (per + 1), spec.index % (per + 1), per + 1});
    } else {
        const auto rest = static_cast<std::uint32_t>(spec.index - in_longer);
        mine.push_back({extra + rest / per, rest % per, per});
    }
    return mine;
}

}  // namespace rtc
