// Replaces the global operator new of the programs linked with it (simulate,
// bench, bench_build; see sim/util/process_memory.h) so that large arrays
// (std::vector's and every other allocation through new) get huge pages when
// the mode says so. Allocation itself is what the standard library does:
// malloc and aligned_alloc, freed with free() by the deletes below. Not built
// under the sanitizers, which replace operator new themselves to check it.
#include "sim/util/process_memory.h"

#include <algorithm>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kDefault = __STDCPP_DEFAULT_NEW_ALIGNMENT__;

// `alignment`: a power of two, at least kDefault (malloc's).
void* allocate(std::size_t bytes, std::size_t alignment = kDefault) {
    if (bytes == 0) bytes = 1;
    // aligned_alloc wants a multiple of the alignment.
    void* p = alignment <= kDefault ? std::malloc(bytes)
                                    : std::aligned_alloc(alignment, (bytes + alignment - 1) & ~(alignment - 1));
    if (!p) throw std::bad_alloc();
    if (bytes >= rtc::kLargeAllocationBytes) rtc::advise_large_allocation(p, bytes);
    return p;
}

}  // namespace

void* operator new(std::size_t bytes) { return allocate(bytes); }
void* operator new[](std::size_t bytes) { return allocate(bytes); }
void* operator new(std::size_t bytes, std::align_val_t a) { return allocate(bytes, std::max(kDefault, static_cast<std::size_t>(a))); }
void* operator new[](std::size_t bytes, std::align_val_t a) { return allocate(bytes, std::max(kDefault, static_cast<std::size_t>(a))); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
    try { return allocate(bytes); } catch (...) { return nullptr; }
}
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept {
    try { return allocate(bytes); } catch (...) { return nullptr; }
}
void* operator new(std::size_t bytes, std::align_val_t a, const std::nothrow_t&) noexcept {
    try { return allocate(bytes, std::max(kDefault, static_cast<std::size_t>(a))); } catch (...) { return nullptr; }
}
void* operator new[](std::size_t bytes, std::align_val_t a, const std::nothrow_t&) noexcept {
    try { return allocate(bytes, std::max(kDefault, static_cast<std::size_t>(a))); } catch (...) { return nullptr; }
}

// The matching deletes: free() for every form, as malloc and aligned_alloc
// need (defined here too, so the pair never depends on the library's choice).
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
