#include "sim/util/process_memory.h"

#include <atomic>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace rtc {

bool keep_freed_memory() {
#if defined(__GLIBC__)
    // mallopt takes an int: INT_MAX (2 GB) is the largest threshold it can
    // set. Both settings are needed: with the mmap threshold alone, the freed
    // top of the heap is still trimmed back to the kernel (measured: 187 k
    // page faults against 137 k with both).
    const bool heap = mallopt(M_MMAP_THRESHOLD, INT_MAX) == 1;
    const bool kept = mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
    return heap && kept;
#else
    return false;
#endif
}

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
constexpr std::size_t kProbeBytes = std::size_t{2} << 20;

std::atomic<HugePages> g_mode{HugePages::Off};

struct Probe {
    double small_seconds = -1.0;  // fresh kProbeBytes with 4 kB pages (best of two)
    double huge_seconds = -1.0;   // the same with MADV_HUGEPAGE
    bool use_huge = false;
};

double best_of_two(bool huge) {
    const double a = fresh_memory_seconds(kProbeBytes, huge);
    const double b = fresh_memory_seconds(kProbeBytes, huge);
    return a < 0.0 || b < 0.0 ? -1.0 : (a < b ? a : b);
}

// Runs once, at the first large allocation under Auto.
const Probe& probe() {
    static const Probe p = [] {
        Probe r;
        r.small_seconds = best_of_two(false);
        r.huge_seconds = best_of_two(true);
        // Only a clear win: within 30 % the probe's noise could decide.
        r.use_huge = r.small_seconds > 0.0 && r.huge_seconds >= 0.0 && r.huge_seconds < 0.7 * r.small_seconds;
        return r;
    }();
    return p;
}

std::atomic<bool> g_probed{false};

// Bytes from `p` to the next 2 MB boundary (0 on one).
std::size_t up_to_huge_page(const void* p) {
    const auto a = reinterpret_cast<std::uintptr_t>(p);
    return static_cast<std::size_t>(((a + kHugePage - 1) & ~(kHugePage - 1)) - a);
}

}  // namespace

double fresh_memory_seconds(std::size_t bytes, bool huge_pages) noexcept {
#if defined(__linux__)
    const std::size_t mapped = bytes + kHugePage;
    void* raw = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) return -1.0;
    char* const aligned = static_cast<char*>(raw) + up_to_huge_page(raw);
    volatile char* p = aligned;
    if (huge_pages) madvise(aligned, bytes, MADV_HUGEPAGE);
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 1;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    munmap(raw, mapped);
    return s;
#else
    (void)bytes, (void)huge_pages;
    return -1.0;
#endif
}

void set_huge_pages(HugePages mode) { g_mode.store(mode, std::memory_order_relaxed); }

bool set_huge_pages_from_environment(const char* program) {
    const char* env = std::getenv("RTCSIM_HUGE_PAGES");
    HugePages mode = HugePages::Auto;
    if (env && *env) {
        if (std::strcmp(env, "off") == 0) mode = HugePages::Off;
        else if (std::strcmp(env, "on") == 0) mode = HugePages::On;
        else if (std::strcmp(env, "auto") != 0) {
            set_huge_pages(HugePages::Off);
            if (program)
                std::fprintf(stderr, "%s: environment variable RTCSIM_HUGE_PAGES is '%s': expected off, on or auto\n",
                             program, env);
            return false;
        }
    }
    set_huge_pages(mode);
    return true;
}

void advise_large_allocation(void* p, std::size_t bytes) noexcept {
#if defined(__linux__)
    const HugePages mode = g_mode.load(std::memory_order_relaxed);
    if (mode == HugePages::Off || !p || bytes < kLargeAllocationBytes) return;
    if (mode == HugePages::Auto) {
        const bool use = probe().use_huge;
        g_probed.store(true, std::memory_order_relaxed);
        if (!use) return;
    }
    // Only whole 2 MB pages inside the block: advice past its ends would
    // reach the heap's other blocks.
    const std::size_t skip = up_to_huge_page(p);
    if (bytes <= skip) return;
    const std::size_t whole = (bytes - skip) & ~std::size_t{kHugePage - 1};
    if (whole > 0) madvise(static_cast<char*>(p) + skip, whole, MADV_HUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}

std::string huge_pages_summary() {
    switch (g_mode.load(std::memory_order_relaxed)) {
    case HugePages::Off: return "off";
    case HugePages::On: return "on";
    case HugePages::Auto: break;
    }
    if (!g_probed.load(std::memory_order_relaxed)) return "auto: not probed yet (no large allocation)";
    const Probe& r = probe();
    char line[160];
    std::snprintf(line, sizeof line, "auto: %s (fresh 2 MB in %.2f ms with 4 kB pages, %.2f ms with huge pages)",
                  r.use_huge ? "on" : "off", r.small_seconds * 1e3, r.huge_seconds * 1e3);
    return line;
}

}  // namespace rtc
