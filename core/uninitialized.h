// A vector whose resize() leaves its elements unconstructed, for arrays whose
// every used slot is written before it is read:
// - the per-pixel and per-ray arrays a frame's tasks fill in parallel
//   (sim/execution/frame.h): zeroing them first was a serial pass, with the
//   page faults of a fresh allocation, in front of every frame (800 x 800
//   pixels of counts are 66 MB, 28 ms on this machine, a third of a frame of
//   cheap rays on one core); now each thread touches the pages it writes;
// - the builder's binary node array (core/build/bvh_build_binary.h), sized
//   for the worst case and written node by node.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtc {

template <class T>
struct UninitializedAllocator : std::allocator<T> {
    template <class U>
    struct rebind { using other = UninitializedAllocator<U>; };
    UninitializedAllocator() = default;
    template <class U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
    // Value-less construction leaves the storage as allocated: only for
    // trivially copyable aggregates and arithmetic types (implicit-lifetime
    // types, whose objects the allocation itself creates), which the owner
    // writes before reading.
    template <class U>
    void construct(U*) noexcept {
        static_assert(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>);
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

template <class T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace rtc
