// Structural solid as q3map2's sun rays meet it. It traces them with testAll, and its TraceLine_r
// then skips every branch of its trace tree that holds no caster triangle: solid leaves in such a
// branch (the inside of thick walls and slabs, whose faces all lie in the open leaves around them)
// do not stop a sun ray, so a grid point under a slab can see the sky past it once the inhibit
// radius hides the slab's faces. A solid leaf the tracer subdivided (it held enough triangles)
// became a plain node and stops no ray.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bspfile.h"
#include "solid_segment_tree.h"
#include "vec3.h"

namespace q3::light {

// Per BSP leaf, what q3map2's trace tree holds there (traceCasterPieces fills it).
struct TraceLeafContents {
    std::vector<uint8_t> holdsPieces;  // some caster winding was filtered into the leaf
    std::vector<uint8_t> subdivided;   // the tracer split the leaf (enough triangles, wide enough)
};

class SkyRaySolid {
public:
    // Keeps a reference to `bsp`, which must outlive it.
    SkyRaySolid(const bsp::Bsp& bsp, const TraceLeafContents& contents);
    // Whether the walk of a sun ray from `from` to `to` (where it meets its sky) reaches a solid
    // leaf, front to back with q3map2's 0.1-unit on-plane epsilon, skipping branches without
    // casters. False without a node tree.
    bool stops(Vec3 from, Vec3 to) const;
    // True when no segment inside the convex hull of `points` can stop as stops() walks it (see
    // SolidSegmentTree::hullWalk); false when unsure.
    bool hullClear(std::span<const Vec3> points) const { return hullWalk(points).clear; }
    // hullClear's answer, and where the walks of segments inside the hull may begin.
    HullVerdict hullWalk(std::span<const Vec3> points) const;
    // stops() of a segment inside a hull that hullWalk did not call clear, begun where it says.
    bool stopsFrom(const HullVerdict& hull, Vec3 from, Vec3 to) const;
    // The plain walk over the BSP lumps that the compact one must match answer for answer (used for
    // trees that are not proper trees, and by the tests).
    bool stopsByPlainWalk(Vec3 from, Vec3 to) const;

private:
    bool stopsBelow(int32_t node, Vec3 start, Vec3 end, int depth) const;

    const bsp::Bsp& bsp_;
    std::vector<uint8_t> nodeHoldsPieces_;  // per node: some leaf below it holds a caster
    std::vector<uint8_t> leafStops_;        // per leaf: outside every cluster and not subdivided
    SolidSegmentTree compact_;              // the same rule for the compact walks
};

}  // namespace q3::light
