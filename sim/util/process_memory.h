// How the simulator's programs (simulate, bench, bench_build) set up the C
// library's memory for runs that build and free arrays of hundreds of MB in
// turn (a method's BVH build scratch, then its per-pixel counts, then the next
// method's build). Process settings, so only the programs' main() call them;
// the Python module and the tests leave their host process's allocator alone.
//
// 1. Keep freed memory. glibc hands every block above 128 kB back to the
//    kernel on free and takes fresh pages for the next one, and each fresh
//    page is a page fault and a zeroed 4 kB. Kept in the heap, the next array
//    reuses the pages. Measured on configs/runs/head_1m.json
//    (docs/benchmark.md, issue 19 round 9): 214 k -> 143 k page faults, the
//    obb build 1.19 -> 0.82-0.94 s.
// 2. Huge pages for large arrays. What is still fresh (every array larger
//    than the heap had before) faults 4 kB at a time. Advised with
//    MADV_HUGEPAGE, it faults 2 MB at a time: the same zeroing, 1/512 of the
//    faults. Whether that pays depends on the machine (round 6's VM built
//    20-50 % slower with huge pages, round 8's and 10's 30-55 % faster), so by
//    default a probe decides: it times faulting fresh memory both ways once,
//    at the first large allocation (docs/benchmark.md, issue 19 round 10).
#pragma once

#include <cstddef>
#include <string>

namespace rtc {

// Serves allocations below 2 GB from the heap and never trims it (peak
// memory stays with the process until it exits). Returns false where the C
// library has no such settings or refused them; the run is then only slower.
bool keep_freed_memory();

enum class HugePages { Off, On, Auto };

// Arrays of at least this many bytes get huge pages when they are on.
inline constexpr std::size_t kLargeAllocationBytes = std::size_t{4} << 20;

// Sets the huge-page mode for large allocations from the environment variable
// RTCSIM_HUGE_PAGES (off, on or auto; auto when unset). Takes effect only in a
// program linked with rtcsim_large_allocations, whose operator new reports
// large allocations to advise_large_allocation(). Returns false, and leaves
// the mode off, when the variable holds anything else; with a `program` name
// (a program's main(), which then exits with 2) it first prints
// "<program>: environment variable RTCSIM_HUGE_PAGES is '<value>': expected
// off, on or auto" to stderr.
bool set_huge_pages_from_environment(const char* program = nullptr);
void set_huge_pages(HugePages mode);

// Advises [p, p + bytes) for huge pages (the 2 MB-aligned part of it) when
// the mode says so; under Auto the first call runs the probe. Allocates
// nothing, so operator new may call it.
void advise_large_allocation(void* p, std::size_t bytes) noexcept;

// One line for the programs' output: the mode and, once decided, what auto
// chose and the probe's figures, e.g. "auto: on (fresh 2 MB in 5.6 ms with
// 4 kB pages, 0.2 ms with huge pages)". "auto: not probed yet" before the
// first large allocation.
std::string huge_pages_summary();

// The probe's measurement: seconds to touch `bytes` of fresh anonymous memory
// (2 MB-aligned) page by page, with or without MADV_HUGEPAGE. Negative when
// the memory could not be mapped.
double fresh_memory_seconds(std::size_t bytes, bool huge_pages) noexcept;

}  // namespace rtc
