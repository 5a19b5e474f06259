// How `simulate CONFIG --shard I/N` splits a run into N independent shards
// whose partial results merge into exactly one run's (docs/scale-out.md).
//
// The work is a list of units, a (sweep point, band) pair, where a band is a
// contiguous range of the frame's tasks (rows of image tiles, or blocks of a
// ray list: the units the frame loop already hands to threads, so a band
// boundary never cuts a warp). With P sweep points and N shards:
//   - P >= N: every point is one unit; shard I runs the points p with
//     p mod N = I (round robin, so a sweep's slow corner is spread out);
//   - P < N: the N shards are dealt over the points, point p getting
//     floor(N / P) bands, plus one for the first N mod P points; shard I
//     runs unit I. A single frame with N shards is N bands of rows.
// The plan depends only on P and N: every shard and the merge agree on it
// without talking to each other.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

struct ShardSpec {
    std::uint32_t index = 0;  // I in 0 .. count - 1
    std::uint32_t count = 1;  // N
};

// Parses "I/N" (0 <= I < N <= 100000); throws InputError naming `option`.
[[nodiscard]] ShardSpec parse_shard_spec(const std::string& text, const std::string& option);

struct ShardUnit {
    std::size_t point = 0;     // sweep point index
    std::uint32_t band = 0;    // band of that point's frame, 0 .. bands - 1
    std::uint32_t bands = 1;   // bands the point's frame is cut into
};

// Every unit of a run with `points` sweep points over `shards` shards, in
// order; unit u belongs to shard u mod shards.
[[nodiscard]] std::vector<ShardUnit> shard_units(std::size_t points, std::uint32_t shards);

// The units shard `spec` runs.
[[nodiscard]] std::vector<ShardUnit> units_of_shard(std::size_t points, const ShardSpec& spec);

}  // namespace rtc
