#include "core/two_level.h"

#include "core/parallel.h"

#include <stdexcept>
#include <string>

namespace rtc {

namespace {

// The identity up to the signs of its zeros (glm's == compares floats:
// -0 == 0; x - (+-0) is x for every x passes_identity lets through).
bool is_identity(const CentredAffine& a) {
    return a.linear == glm::mat3(1.0f) && a.origin == Vec3(0.0f);
}

// See TwoLevel::lone_identity.
bool has_lone_identity(const TwoLevel& s) {
    const Bvh& t = s.tlas;
    if (t.root.count != (BvhEntry::kInnerBit | 1u) || t.entries[t.root.first].is_inner()) return false;
    const BvhEntry& leaf = t.entries[t.root.first];
    if (leaf.count != 1) return false;
    const TlasInstance& inst = s.instances[leaf.first];  // leaf slot = instance (TwoLevel::instances)
    const Bvh& blas = s.blases[inst.blas];
    return is_identity(inst.object_from_world) && (blas.root.count & BvhEntry::kInnerBit) &&
           !detail::one_leaf(blas);
}

// The error of an instance whose BLAS index is past the BLASes.
std::invalid_argument no_blas(std::size_t instance, std::uint32_t blas) {
    return std::invalid_argument("instance " + std::to_string(instance) + ": no BLAS " + std::to_string(blas));
}

}  // namespace

Instance make_instance(std::uint32_t blas, std::uint32_t id, const Affine& world_from_object) {
    const auto inverse = centred_inverse(world_from_object);
    if (!inverse)
        throw std::invalid_argument("instance " + std::to_string(id) +
                                    ": transform is singular or not finite");
    return {blas, id, world_from_object, *inverse};
}

TwoLevel build_two_level(std::vector<Bvh> blases, std::size_t count,
                         const std::function<Instance(std::size_t)>& instance,
                         const BuildOptions& tlas_options) {
    const unsigned threads = tlas_options.threads > 0 ? static_cast<unsigned>(tlas_options.threads) : 0;
    UninitializedVector<Aabb> boxes(count);
    parallel_for(count, threads, [&](std::size_t i, unsigned) {
        const Instance in = instance(i);
        if (in.blas >= blases.size()) throw no_blas(i, in.blas);
        const Aabb& root = blases[in.blas].bounds();
        // An instance of an empty BLAS gets a point box: it is never entered
        // usefully but keeps instance indices and TLAS leaves one to one.
        boxes[i] = root.empty() ? Aabb::from_point(in.world_from_object.translation)
                                : in.world_from_object.box(root);
    });
    TwoLevel out{std::move(blases), {}, build_bvh(boxes, tlas_options)};
    // The instances in the TLAS's leaf order (and the leaves' primitive ids
    // the identity): a leaf's instance is then the one at its own slot, next
    // to its tree neighbours' (docs/benchmark.md, issue 19 round 9: the head
    // frame's obb trace, 1 M instances, about 12 % faster). Indices are internal:
    // programs get the instance's id.
    out.instances.resize(count);
    parallel_for(count, threads, [&](std::size_t k, unsigned) {
        const Instance in = instance(out.tlas.prim_ids[k]);
        out.instances[k] = {in.object_from_world, in.blas, in.id};
        out.tlas.prim_ids[k] = static_cast<std::uint32_t>(k);
    });
    out.lone_identity = has_lone_identity(out);
    return out;
}

TwoLevel build_two_level(std::vector<Bvh> blases, std::span<const Instance> instances,
                         const BuildOptions& tlas_options) {
    // Checked in index order first, so that the error names the first bad instance.
    for (std::size_t i = 0; i < instances.size(); ++i)
        if (instances[i].blas >= blases.size()) throw no_blas(i, instances[i].blas);
    return build_two_level(std::move(blases), instances.size(),
                           [instances](std::size_t i) { return instances[i]; }, tlas_options);
}

std::size_t TwoLevel::memory_bytes() const {
    std::size_t bytes = tlas.memory_bytes() + instances.capacity() * sizeof(TlasInstance);
    for (const Bvh& b : blases) bytes += b.memory_bytes();
    return bytes;
}

}  // namespace rtc
