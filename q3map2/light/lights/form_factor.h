// The area-light form factor (q3map2 PointToPolygonFormFactor) and the cheap bound that lets most
// far pairs skip it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "lights.h"
#include "vec3.h"

namespace q3::light {

// Fraction of the hemisphere above (point, normal) covered by the polygon, signed by facing
// (q3map2 PointToPolygonFormFactor). 0 for degenerate polygons. Edges are taken four at a time
// where the CPU has 4-wide vectors, with the float operations of the one-edge form in the same
// order, so that both give the same bits.
float pointToPolygonFormFactor(Vec3 point, Vec3 normal, std::span<const Vec3> winding);
// The one-edge-at-a-time form: the reference for the vector form, and its fallback.
float pointToPolygonFormFactorScalar(Vec3 point, Vec3 normal, std::span<const Vec3> winding);

// Four points, each with its normal, as lanes of their coordinates.
struct FormFactorPoints {
    alignas(16) float x[4], y[4], z[4], nx[4], ny[4], nz[4];
};
// pointToPolygonFormFactor at four points at once: `out[l]` has the bits of the one-point form at
// point l. The lanes walk the polygon's edges together: each edge is worked out for all four.
void pointToPolygonFormFactor4(const FormFactorPoints& points, std::span<const Vec3> winding, float out[4]);

namespace detail {

// area x receiver cosine x emitter cosine / (pi d^2), every factor bounded over the polygon, from
// `nearest`, no more than the distance to any of its points, and `reach`, no less than any
// |normal . (corner - point)|. Unbounded closer than one unit.
inline float boundFrom(const EmitterBounds& b, Vec3 point, float nearest, float reach) {
    if (!(nearest > 1.0f)) return std::numeric_limits<float>::infinity();
    const float receiver = std::min(1.0f, reach / nearest);
    const float emitter =
        b.flat ? std::min(1.0f, (std::fabs(dot(b.center - point, b.planeNormal)) + b.flatness) / nearest) : 1.0f;
    return b.area * receiver * emitter / (kPi * nearest * nearest);
}

}  // namespace detail

// A bound no smaller than |pointToPolygonFormFactor(point, normal, winding)| for the polygon of
// `bounds` (unit `normal`): area x cosine bounds / (pi d^2) from the nearest possible distance d.
// Infinity when the point may lie inside the bounding sphere or the bounds are unknown. Inline:
// every (luxel, area light) pair in reach asks it.
inline float formFactorUpperBound(const EmitterBounds& b, Vec3 point, Vec3 normal) {
    if (b.radius < 0) return std::numeric_limits<float>::infinity();
    // The corners' box: the nearest of its points, and the normal's extremes over its corners.
    const Vec3 nearestInBox = vmin(vmax(point, b.box.mins), b.box.maxs);
    float lo = 0, hi = 0;
    for (int k = 0; k < 3; ++k) {
        const float a = normal[k] * (b.box.mins[k] - point[k]), c = normal[k] * (b.box.maxs[k] - point[k]);
        lo += std::min(a, c);
        hi += std::max(a, c);
    }
    // Room for the float rounding of the exact evaluation.
    const float reach = std::max(std::fabs(lo), std::fabs(hi));
    return detail::boundFrom(b, point, distance(nearestInBox, point), reach) * 1.02f + 1e-5f;
}

}  // namespace q3::light
