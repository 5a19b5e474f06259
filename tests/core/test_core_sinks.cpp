// EventTotals::add_all, the frame's per-row sum, against add() per item: the
// same 64-bit totals whether the 32-bit chunk sums are exact (small counts)
// or would wrap (counts of 2^24 and more, which take the 64-bit path).
#include "core/sinks.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;

namespace {

EventTotals one_by_one(const std::vector<RayCounts>& counts) {
    EventTotals t;
    for (const RayCounts& c : counts) t.add(c);
    return t;
}

EventTotals all_at_once(const std::vector<RayCounts>& counts) {
    EventTotals t;
    t.add_all(counts.data(), counts.size());
    return t;
}

// Counts, in `seen`, the events events_of_unit<U, Others> lists, checking
// each is of unit U (of another unit with Others) and the list is in order.
template <EventUnit U, bool Others = false>
void check_unit_list(std::vector<int>& seen) {
    constexpr auto list = events_of_unit<U, Others>();
    for (std::size_t k = 0; k < list.size(); ++k) {
        CAPTURE(k);
        CHECK((event_unit(static_cast<Event>(list[k])) == U) != Others);
        if (k > 0) CHECK(list[k - 1] < list[k]);
        ++seen[list[k]];
    }
}

}  // namespace

TEST_CASE("sinks: add_all equals add per item, with and without counts that would wrap 32 bits") {
    Rng rng(7);
    for (const std::size_t items : {0u, 1u, 255u, 256u, 257u, 1000u}) {
        std::vector<RayCounts> small(items), large(items);
        for (std::size_t r = 0; r < items; ++r)
            for (std::size_t i = 0; i < kEventCount; ++i) {
                small[r].n[i] = static_cast<std::uint32_t>(rng.gen() >> 8);  // < 2^24
                large[r].n[i] = small[r].n[i];
            }
        CHECK(all_at_once(small) == one_by_one(small));
        if (items == 0) continue;
        // From the second item on: 104 bytes in, not 16-byte aligned (the
        // vector path's unaligned loads), and an odd or even count.
        const std::vector<RayCounts> tail(small.begin() + 1, small.end());
        EventTotals from_second;
        from_second.add_all(small.data() + 1, items - 1);
        CHECK(from_second == one_by_one(tail));
        // One count at the 2^24 limit, and one near 2^32, in the last chunk:
        // 256 such rows would wrap a 32-bit sum many times over.
        large[items - 1].n[3] = 1u << 24;
        large[items / 2].n[5] = 0xFFFFFFF0u;
        const EventTotals want = one_by_one(large);
        CHECK(all_at_once(large) == want);
        CHECK(want[static_cast<Event>(5)] >= 0xFFFFFFF0ull);
    }
    // Every count at the maximum: the 64-bit path over whole chunks.
    std::vector<RayCounts> full(600);
    for (RayCounts& c : full) c.n.fill(0xFFFFFFFFu);
    const EventTotals sum = all_at_once(full);
    CHECK(sum == one_by_one(full));
    CHECK(sum[static_cast<Event>(0)] == 600ull * 0xFFFFFFFFull);
}

TEST_CASE("events: events_of_unit lists every event of a unit once, in order, and with Others the rest") {
    std::vector<int> seen(kEventCount, 0);
    check_unit_list<EventUnit::Shader>(seen);
    check_unit_list<EventUnit::RtUnit>(seen);
    check_unit_list<EventUnit::HandOff>(seen);
    check_unit_list<EventUnit::Program>(seen);
    CHECK(seen == std::vector<int>(kEventCount, 1));
    std::vector<int> split(kEventCount, 0);
    check_unit_list<EventUnit::Program>(split);
    check_unit_list<EventUnit::Program, /*Others=*/true>(split);
    CHECK(split == std::vector<int>(kEventCount, 1));
    CHECK(events_of_unit<EventUnit::Shader>()[0] == static_cast<std::uint8_t>(Event::Ray));
}

}  // namespace RTCSIM_TEST_FILE
