#include "sim/hardware/call_profiles.h"

#include <algorithm>
#include <stdexcept>

namespace rtc {

namespace {

std::uint64_t hash_counts(const ProgramCounts& c) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the counts
    for (const std::uint32_t v : c.n) h = (h ^ v) * 1099511628211ull;
    return h;
}

}  // namespace

CallProfiles::Id CallProfiles::find_or_add(const ProgramCounts& c) {
    const auto found = [&](Id i) {
        last_ = i;
        last_counts_ = c;
        has_last_ = true;
        return i;
    };
    // Most frames have a few profiles: a short scan beats hashing.
    const std::size_t few = std::min<std::size_t>(profiles_.size(), 8);
    for (std::size_t i = 0; i < few; ++i)
        if (profiles_[i] == c) return found(static_cast<Id>(i));
    const std::uint64_t h = hash_counts(c);
    const auto [lo, hi] = index_.equal_range(h);
    for (auto it = lo; it != hi; ++it)
        if (profiles_[it->second] == c) return found(it->second);
    if (profiles_.size() > 0xFFFF)
        throw std::length_error("more than 65,536 distinct intersection-program call profiles");
    const auto id = static_cast<Id>(profiles_.size());
    profiles_.push_back(c);
    index_.emplace(h, id);
    return found(id);
}

}  // namespace rtc
