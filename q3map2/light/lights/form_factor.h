// The area-light form factor (q3map2 PointToPolygonFormFactor) and the cheap bound that lets most
// far pairs skip it.
#pragma once

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

// A bound no smaller than |pointToPolygonFormFactor(point, normal, winding)| for the polygon of
// `bounds` (unit `normal`): area x cosine bounds / (pi d^2) from the nearest possible distance d.
// Infinity when the point may lie inside the bounding sphere or the bounds are unknown.
float formFactorUpperBound(const EmitterBounds& bounds, Vec3 point, Vec3 normal);

}  // namespace q3::light
