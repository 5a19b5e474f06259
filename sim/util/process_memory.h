// How the simulator's programs (simulate, bench) ask the C library to keep
// the memory they free. A run builds and frees arrays of hundreds of MB in
// turn (a method's BVH build scratch, then its per-pixel counts, then the next
// method's build). glibc hands every block above 128 kB to the kernel on free
// and takes fresh pages for the next one, and each fresh page is a page fault
// and a zeroed 4 kB. Kept in the heap, the next array reuses the pages.
// Measured on configs/runs/head_1m.json (docs/benchmark.md, issue 19
// round 9): 214 k -> 143 k page faults, the obb build 1.19 -> 0.82-0.94 s.
//
// A process setting, so only the programs' main() call it; the Python module
// leaves its host process's allocator alone.
#pragma once

namespace rtc {

// Serves allocations below 2 GB from the heap and never trims it (peak
// memory stays with the process until it exits). Returns false where the C
// library has no such settings or refused them; the run is then only slower.
bool keep_freed_memory();

}  // namespace rtc
