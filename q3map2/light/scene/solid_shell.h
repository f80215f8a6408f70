// Convex cells around the structural solid that point-light segments' walks can meet, so that a
// segment that meets no cell needs no walk (trace_scene.h asks Embree which segments meet one).
#pragma once

#include <cstdint>
#include <vector>

#include "convex_cell.h"
#include "vec3.h"

namespace q3 {
namespace bsp {
struct Model;
}
namespace light {

class BspTree;

// Cells around every place where BspTree::segmentCrossesSolidFrom's walk of a segment with both
// ends inside `region` can meet solid, with room to spare (the walk's on-plane epsilon and the
// rounding of its split points and of the segment's own points): a segment that meets no cell
// enters no solid. No cells: every segment is walked.
struct SolidShell {
    Bounds region;
    std::vector<Bounds> boxes;         // each cell's bounds
    std::vector<uint32_t> firstPlane;  // cell c: planes[firstPlane[c] .. firstPlane[c + 1])
    std::vector<ConvexCell::Plane> planes;

    bool empty() const { return boxes.empty() || firstPlane.size() != boxes.size() + 1; }
    // Whether the points org + t * dir with t0 <= t <= t1 meet the cell (clipped plane by plane,
    // in double).
    bool segmentMeetsCell(size_t cell, const DVec3& org, const DVec3& dir, double t0, double t1) const;
    // Whether the segment meets some cell, every cell asked in turn (what Embree's search over the
    // cells answers faster).
    bool segmentMeetsAnyCell(Vec3 from, Vec3 to) const;
};

// The shell of `tree`'s walks over the world model's box with a margin (empty without a model,
// with a box not finite or beyond a million units, or without compact walks).
SolidShell solidShellOf(const bsp::Model* world, const BspTree& tree);

}  // namespace light
}  // namespace q3
