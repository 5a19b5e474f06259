// The programs' memory settings (sim/util/process_memory.h): the huge-page
// advice reaches the kernel for the whole 2 MB pages inside a large block and
// nowhere else, the modes and RTCSIM_HUGE_PAGES are honoured, and the probe
// measures. The tests' own allocator is left alone (rtcsim_tests does not
// link the programs' operator new): these call the advice directly.
#include "sim/util/process_memory.h"

#include <doctest/doctest.h>

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

// The VmFlags of the mapping holding `address`, from /proc/self/smaps.
std::string vm_flags(const void* address) {
    const auto a = reinterpret_cast<std::uintptr_t>(address);
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t lo = 0, hi = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> lo >> dash >> hi && dash == '-') {
            inside = lo <= a && a < hi;
        } else if (inside && line.rfind("VmFlags:", 0) == 0) {
            return line;
        }
    }
    return {};
}

bool advised(const void* address) { return vm_flags(address).find(" hg") != std::string::npos; }

struct Mapping {
    static constexpr std::size_t kBytes = std::size_t{16} << 20;
    char* raw = static_cast<char*>(mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
    ~Mapping() { munmap(raw, kBytes); }
    // The first 2 MB boundary inside, plus `offset`.
    char* at(std::size_t offset) const {
        constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
        return reinterpret_cast<char*>((reinterpret_cast<std::uintptr_t>(raw) + huge - 1) & ~(huge - 1)) + offset;
    }
};

// Whether this kernel takes the advice at all (built with transparent huge
// pages); the mode's tests need it, the environment's do not.
bool kernel_takes_advice() {
    const Mapping m;
    return m.raw != MAP_FAILED && madvise(m.at(0), std::size_t{2} << 20, MADV_HUGEPAGE) == 0;
}

struct ModeGuard {
    ~ModeGuard() { set_huge_pages(HugePages::Off); }
};

}  // namespace

TEST_CASE("huge pages: a large block's whole 2 MB pages are advised, and nothing outside them") {
    if (!kernel_takes_advice()) {
        MESSAGE("skipped: this kernel has no transparent huge pages");
        return;
    }
    ModeGuard guard;
    Mapping m;
    REQUIRE(m.raw != MAP_FAILED);
    REQUIRE(!vm_flags(m.at(0)).empty());
    set_huge_pages(HugePages::On);
    // A block from 4 kB past a boundary B0 to 4 kB past B3 (6 MB) holds two
    // whole 2 MB pages, [B1, B3); its partial first and last pages stay as
    // they were.
    constexpr std::size_t mb = std::size_t{1} << 20;
    char* block = m.at(4096);
    advise_large_allocation(block, 6 * mb);
    CHECK_FALSE(advised(block));          // the partial first page
    CHECK(advised(m.at(2 * mb)));         // B1
    CHECK(advised(m.at(6 * mb - 1)));     // just below B3
    CHECK_FALSE(advised(m.at(6 * mb)));   // the partial last page
    // Below the large-allocation size nothing is advised, even with whole pages inside.
    advise_large_allocation(m.at(8 * mb), kLargeAllocationBytes - 1);
    CHECK_FALSE(advised(m.at(8 * mb)));
    // Off advises nothing.
    set_huge_pages(HugePages::Off);
    advise_large_allocation(m.at(8 * mb), 4 * mb);
    CHECK_FALSE(advised(m.at(8 * mb)));
    CHECK(huge_pages_summary() == "off");
}

TEST_CASE("huge pages: RTCSIM_HUGE_PAGES sets the mode, and anything else is refused and leaves it off") {
    ModeGuard guard;
    const char* saved = std::getenv("RTCSIM_HUGE_PAGES");
    const std::string old = saved ? saved : "";
    setenv("RTCSIM_HUGE_PAGES", "on", 1);
    CHECK(set_huge_pages_from_environment());
    CHECK(huge_pages_summary() == "on");
    setenv("RTCSIM_HUGE_PAGES", "sometimes", 1);
    CHECK_FALSE(set_huge_pages_from_environment());
    CHECK(huge_pages_summary() == "off");
    unsetenv("RTCSIM_HUGE_PAGES");
    CHECK(set_huge_pages_from_environment());  // unset: auto
    CHECK(huge_pages_summary().rfind("auto", 0) == 0);
    if (saved) setenv("RTCSIM_HUGE_PAGES", old.c_str(), 1);
}

TEST_CASE("huge pages: auto decides once, by the probe, and says what it measured") {
    if (!kernel_takes_advice()) {
        MESSAGE("skipped: this kernel has no transparent huge pages");
        return;
    }
    ModeGuard guard;
    CHECK(fresh_memory_seconds(std::size_t{2} << 20, false) >= 0.0);
    CHECK(fresh_memory_seconds(std::size_t{2} << 20, true) >= 0.0);
    set_huge_pages(HugePages::Auto);
    Mapping m;
    REQUIRE(m.raw != MAP_FAILED);
    advise_large_allocation(m.at(0), std::size_t{8} << 20);
    const std::string summary = huge_pages_summary();
    CHECK(summary.find("ms with 4 kB pages") != std::string::npos);
    // The advice follows the probe's choice.
    const bool on = summary.rfind("auto: on", 0) == 0;
    CHECK((on || summary.rfind("auto: off", 0) == 0));
    CHECK(advised(m.at(0)) == on);
}

}  // namespace RTCSIM_TEST_FILE
