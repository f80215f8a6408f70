// Rays through the BSP tree against opaque brushes: the zero-size-box case of Quake 3's box trace.
// The segment is split at each node plane and the halves walked near side first; in each leaf
// every opaque brush is clipped against the whole ray (each side plane narrows the interval where
// the ray is behind all planes), so the result does not depend on how the tree cut the ray.
#include <algorithm>

#include "bsp_collision.h"

namespace q3::sh {
namespace {

// Hits are reported this far before the surface, as Quake 3 does, so that a ray ending on a face
// counts as touching it and rounding never lets a ray slip between two brushes sharing a face.
constexpr float kClipEpsilon = 0.125f;
// Both halves of a split overlap by this distance, so leaves along the plane are walked from both.
constexpr float kSplitEpsilon = 0.125f;

struct Ray {
    float start[3];
    float end[3];
    bool stopAtAny;
};

float planeDistance(const CollisionPlane& p, const float v[3]) {
    return p.normal[0] * v[0] + p.normal[1] * v[1] + p.normal[2] * v[2] - p.dist;
}

// Where the ray enters `brush` (fraction, side), or false when it misses it or starts inside.
bool clipRayToBrush(const BspCollision& world, const CollisionBrush& brush, const Ray& ray, float& enter, bool& sky) {
    float enterAt = -1, leaveAt = 1;
    bool startsOutside = false;
    bool enterSky = false;
    for (uint32_t s = 0; s < brush.sideCount; ++s) {
        const CollisionSide& side = world.sides[brush.firstSide + s];
        const CollisionPlane& plane = world.planes[side.plane];
        const float d0 = planeDistance(plane, ray.start), d1 = planeDistance(plane, ray.end);
        if (d0 > 0) startsOutside = true;
        // Entirely in front of one side of a convex brush: outside the brush everywhere.
        if (d0 > 0 && (d1 >= kClipEpsilon || d1 >= d0)) return false;
        if (d0 <= 0 && d1 <= 0) continue;  // behind this side all along: it does not limit the ray
        if (d0 > d1) {  // crossing into the back of this side
            const float f = std::max(0.0f, (d0 - kClipEpsilon) / (d0 - d1));
            if (f > enterAt) {
                enterAt = f;
                enterSky = side.sky;
            }
        } else {  // crossing out
            leaveAt = std::min(leaveAt, (d0 + kClipEpsilon) / (d0 - d1));
        }
    }
    if (!startsOutside || enterAt < 0 || enterAt >= leaveAt) return false;
    enter = enterAt;
    sky = enterSky;
    return true;
}

void traceLeaf(const BspCollision& world, const CollisionLeaf& leaf, const Ray& ray, RayHit& hit) {
    for (uint32_t k = 0; k < leaf.brushCount; ++k) {
        float enter = 1;
        bool sky = false;
        if (!clipRayToBrush(world, world.brushes[world.leafBrushes[leaf.firstBrush + k]], ray, enter, sky)) continue;
        if (hit.hit && enter >= hit.fraction) continue;
        hit = {true, enter, sky};
        if (ray.stopAtAny) return;
    }
}

// Walks the part [f0, f1] of the ray (points p0, p1) through the subtree `index`.
void traceNode(const BspCollision& world, int32_t index, float f0, float f1, const float p0[3], const float p1[3],
               const Ray& ray, RayHit& hit) {
    // Nothing further along can come before what was already hit.
    if (hit.hit && (ray.stopAtAny || hit.fraction <= f0)) return;
    if (index < 0) {
        traceLeaf(world, world.leafs[-1 - index], ray, hit);
        return;
    }
    const CollisionNode& node = world.nodes[index];
    const CollisionPlane& plane = world.planes[node.plane];
    const float d0 = planeDistance(plane, p0), d1 = planeDistance(plane, p1);
    if (d0 >= kSplitEpsilon && d1 >= kSplitEpsilon) return traceNode(world, node.children[0], f0, f1, p0, p1, ray, hit);
    if (d0 < -kSplitEpsilon && d1 < -kSplitEpsilon) return traceNode(world, node.children[1], f0, f1, p0, p1, ray, hit);
    if (d0 == d1) {  // along the plane: both sides
        traceNode(world, node.children[0], f0, f1, p0, p1, ray, hit);
        traceNode(world, node.children[1], f0, f1, p0, p1, ray, hit);
        return;
    }
    const int nearSide = d0 < d1 ? 1 : 0;  // the side the part starts on
    const float cross = d0 / (d0 - d1), margin = kSplitEpsilon / std::abs(d0 - d1);
    const float nearEnd = std::clamp(cross + margin, 0.0f, 1.0f), farStart = std::clamp(cross - margin, 0.0f, 1.0f);
    float mid[3];
    for (int axis = 0; axis < 3; ++axis) mid[axis] = p0[axis] + (p1[axis] - p0[axis]) * nearEnd;
    traceNode(world, node.children[nearSide], f0, f0 + (f1 - f0) * nearEnd, p0, mid, ray, hit);
    for (int axis = 0; axis < 3; ++axis) mid[axis] = p0[axis] + (p1[axis] - p0[axis]) * farStart;
    traceNode(world, node.children[nearSide ^ 1], f0 + (f1 - f0) * farStart, f1, mid, p1, ray, hit);
}

}  // namespace

RayHit traceRay(const BspCollision& world, const float start[3], const float end[3], bool stopAtAny) {
    RayHit hit;
    if (world.nodes.empty()) return hit;
    const Ray ray{{start[0], start[1], start[2]}, {end[0], end[1], end[2]}, stopAtAny};
    traceNode(world, 0, 0, 1, ray.start, ray.end, ray, hit);
    return hit;
}

}  // namespace q3::sh
