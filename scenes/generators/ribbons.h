// Strands tessellated into flat ribbons of triangles: grass blades, hair
// cards, the thin and arbitrarily oriented triangles that game and film
// scenes are full of and that oriented boxes fit far better than axis-aligned
// ones (Kern et al. 2025, "DOBB-BVH"; rt-hardware.md section 5). Each link
// becomes a quad of width 2 x radius (two triangles; one where an end's
// radius is 0, at a tapered tip), every ribbon of a strand facing one side
// direction, drawn per strand at random perpendicular to the strand's
// root-to-tip axis. A pure function of the strands and the seed.
#pragma once

#include "scenes/scene.h"

#include <cstdint>

namespace rtc {

// Appends the ribbons of `strands` to `mesh` (vertices and triangles).
void append_ribbons(const Strands& strands, std::uint64_t seed, TriangleMesh& mesh);

}  // namespace rtc
