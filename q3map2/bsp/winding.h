// Convex polygons ("windings") and the clipping operations the BSP stage is built on. Points go
// clockwise seen from the front of their plane, as q3map2's windings do, so that the plane of the
// first three points (windingPlane) is the polygon's own plane.
#pragma once

#include <utility>
#include <vector>

#include "dvec3.h"

namespace q3::bspstage {

using Winding = std::vector<DVec3>;

// Far enough that a base winding covers the whole world (q3map2's MAX_WORLD_COORD).
inline constexpr double kMaxWorldCoord = 65536;
// Side tests, face clipping and filtering (q3map2 ON_EPSILON).
inline constexpr double kOnEpsilon = 0.1;
// Portal clipping against a node's existing portals (q3map2 CLIP_EPSILON).
inline constexpr double kClipEpsilon = 0.1;

enum class PlaneSide { Front = 0, Back = 1, On = 2, Cross = 3 };

// A quad on the plane far larger than the world (q3map2 BaseWindingForPlane).
Winding baseWindingForPlane(const DPlane& plane);

// For brush windings: the corners of the bounds' footprint across the plane's dominant axis, lifted
// onto the plane along it, in q3map2's order (BaseWindingForPlaneAccu with the brush's box). Exact
// for axial planes; empty when no component of the normal dominates or the bounds are empty.
Winding baseWindingForPlaneInBounds(const DPlane& plane, const DBounds& bounds);
// Keeps the part in front of the plane. Points within `epsilon` count as on it; the winding
// empties when nothing is in front. Like every operation here except the "Accurate" ones, it
// works as q3map2's float windings do (distances in 32-bit floats, new points rounded to floats).
void chopWindingInPlace(Winding& w, const DPlane& plane, double epsilon);
// The same in double precision, never closer than half a float epsilon: for brush windings.
void chopWindingInPlaceAccurate(Winding& w, const DPlane& plane, double epsilon);
// Splits into (front, back). Strict: a winding lying on the plane gives two empty windings.
std::pair<Winding, Winding> clipWindingStrict(const Winding& w, const DPlane& plane, double epsilon);
// As above, but a winding on the plane comes back whole on the back side.
std::pair<Winding, Winding> clipWinding(const Winding& w, const DPlane& plane, double epsilon);
// Where the winding lies relative to the plane, with kOnEpsilon.
PlaneSide windingOnPlaneSide(const Winding& w, const DPlane& plane);

// Fewer than three edges longer than 0.2: vertex snapping would crush it.
bool windingIsTiny(const Winding& w);
double windingArea(const Winding& w);
DVec3 windingCenter(const Winding& w);
DBounds windingBounds(const Winding& w);
Winding reverseWinding(const Winding& w);
// Plane of the first three points.
DPlane windingPlane(const Winding& w);
// Merges edges shorter than 0.1, preferring coordinates within 0.01 of an integer.
void weldShortEdges(Winding& w);
// Grows `hull` (convex, on the plane with `normal`) to the convex hull of itself and `w`.
void addWindingToConvexHull(const Winding& w, Winding& hull, const DVec3& normal);
// True when two windings on the same plane (with `normal`) overlap by more than a sliver.
bool coplanarWindingsIntersect(const Winding& a, const Winding& b, const DVec3& normal);

}  // namespace q3::bspstage
