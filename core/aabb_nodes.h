// The axis-aligned node style of the traversal kernel (core/traverse.h): a
// node's children are the lane blocks of Bvh::lanes, tested by one box test
// (core/box_test.h) four children per instruction.
#pragma once

#include "core/box_test.h"
#include "core/child_hit.h"
#include "core/bvh.h"
#include "core/events.h"

#include <cstdint>

namespace rtc {

template <class BoxTest = BlockBoxTest>
class AabbNodes {
public:
    using Tmax = typename BoxTest::Tmax;

    AabbNodes(const Bvh& bvh, const Vec3& origin, const Vec3& inv_dir, float tmin)
        : lanes_(bvh.lanes.data()), root_count_(bvh.root.count), ray_(origin, inv_dir, tmin) {}

    // The root node's blocks come first (make_lanes).
    [[nodiscard]] BvhLaneBlock::Child root() const { return {0, root_count_}; }

    // Counts and tests the n children of the node whose blocks start at `first`.
    [[nodiscard, gnu::always_inline]] static Tmax tmax(float t) { return BoxTest::tmax(t); }

    template <Event kBoxTest, class Sink>
    [[nodiscard, gnu::always_inline]] unsigned test(std::uint32_t first, std::uint32_t n, Sink& sink, Tmax tmax,
                                                    float* tnear) {
        sink.add(kBoxTest, n);
        // The ray's broadcasts, as far as the compiler knows, changed in
        // memory: each box test reads them as operands of its subtracts and
        // multiplies (no extra instruction). Held in registers, they were
        // live across every leaf, whose calls clobber all vector registers,
        // and were saved and restored at each leaf (obb's instance leaves: 14
        // moves each; cases 1 and 3 obb 4 % fewer instructions per ray).
        asm("" : "+m"(ray_));
        return BoxTest::children(lanes_ + first, n, ray_, tmax, tnear);
    }

    // descend(child), child(i) = hit child i as a ChildHit.
    template <class Descend>
    [[nodiscard, gnu::always_inline]] ChildHit children(std::uint32_t first, std::uint32_t n, const float* tnear,
                                                        Descend&& descend) const {
        const BvhLaneBlock* block = lanes_ + first;
        // One block (the default width): no block index per child (case 1
        // and 2: 3-4 % fewer instructions per ray).
        const auto in_one_block = [&](std::uint32_t i) {
            return ChildHit{child_word(block->child[i & 3u]), tnear[i & 3u]};
        };
        const auto in_blocks = [&](std::uint32_t i) {
            return ChildHit{child_word(block[i / 4].child[i % 4]), tnear[i]};
        };
        return n <= 4 ? descend(in_one_block) : descend(in_blocks);
    }

private:
    const BvhLaneBlock* lanes_;
    std::uint32_t root_count_;
    typename BoxTest::Ray ray_;
};

}  // namespace rtc
