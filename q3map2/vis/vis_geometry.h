// The geometry of portal vis: planes, fixed-capacity windings, chopping a winding by a plane and
// the separating planes between two portals. Single precision like q3map2, with its 0.1 unit
// on-plane epsilon, so that plane tests land on the same side as the reference's.
#pragma once

#include "vec3.h"

#include <array>
#include <span>

namespace q3::vis {

constexpr float kOnEpsilon = 0.1f;
// A chopped winding never holds more than this; a chop that would need more keeps its input
// (unclipped, so the result stays conservative). The .prt allows 64 points per portal.
constexpr int kMaxWindingPoints = 80;
// One separator per source edge at most.
constexpr int kMaxSeparators = kMaxWindingPoints;

struct Plane {
    Vec3 normal;
    float dist = 0;

    float distanceTo(Vec3 p) const { return dot(normal, p) - dist; }
    Plane flipped() const { return {-normal, -dist}; }
};

struct Winding {
    int count = 0;
    std::array<Vec3, kMaxWindingPoints> points;

    std::span<const Vec3> view() const { return {points.data(), static_cast<size_t>(count)}; }
};

// The plane through a, b, c with normal (c - a) x (b - a), as q3map2's PlaneFromPoints. False
// (and the plane untouched) when the points are collinear.
bool planeFromPoints(Plane& plane, Vec3 a, Vec3 b, Vec3 c);

// Keeps the part of `in` in front of `split` (points within kOnEpsilon count as on it).
// Returns `in` when nothing is behind, nullptr when nothing is in front, else `out` filled.
const Winding* chopWinding(const Winding* in, const Plane& split, Winding* out);

// The plane through edge `edge` (points edge, edge + 1) of `source` and the first point of `pass`
// that has all of `source` behind and all of `pass` in front (flipped when `flip`). False when
// no point of `pass` gives one.
bool findSeparator(const Winding& source, const Winding& pass, int edge, bool flip, Plane& out);

// findSeparator for every edge of `source`; returns the count written to `out` (which holds
// kMaxSeparators).
int findSeparators(const Winding& source, const Winding& pass, bool flip, Plane* out);

// Centre of the points and the largest distance from it, for quick sphere-against-plane tests.
void boundingSphere(const Winding& w, Vec3& origin, float& radius);

}  // namespace q3::vis
