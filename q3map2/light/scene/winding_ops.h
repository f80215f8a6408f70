// Convex windings (polygons) as the light stage's area emitters use them: bounds, area, centre
// and the axial split that chops an emitter into pieces. Generic over the vertex type so that a
// plain point winding and a winding carrying texture/lightmap coordinates share one split; a
// `positionOf` functor gives (mutable and const) access to a vertex's xyz.
#pragma once

#include <cstddef>
#include <vector>

#include "vec3.h"

namespace q3::light {

// Identity accessor for windings of plain points.
struct PointPosition {
    Vec3& operator()(Vec3& p) const { return p; }
    const Vec3& operator()(const Vec3& p) const { return p; }
};

template <class Vertex, class PositionOf = PointPosition>
Bounds windingBounds(const std::vector<Vertex>& w, PositionOf positionOf = {}) {
    Bounds b;
    for (const Vertex& v : w) b.add(positionOf(v));
    return b;
}

// Area of a convex winding as a fan of triangles around its first point.
template <class Vertex, class PositionOf = PointPosition>
float windingArea(const std::vector<Vertex>& w, PositionOf positionOf = {}) {
    float area = 0;
    for (size_t i = 2; i < w.size(); ++i) {
        const Vec3 origin = positionOf(w[0]);
        area += 0.5f * length(cross(positionOf(w[i - 1]) - origin, positionOf(w[i]) - origin));
    }
    return area;
}

// Mean of the winding's points (q3map2 WindingCenter), not the centre of its bounds.
template <class Vertex, class PositionOf = PointPosition>
Vec3 windingCentroid(const std::vector<Vertex>& w, PositionOf positionOf = {}) {
    Vec3 sum;
    for (const Vertex& v : w) sum += positionOf(v);
    return w.empty() ? sum : sum / static_cast<float>(w.size());
}

// Splits `w` by the axial plane (axis, dist) into the part above (`front`) and below (`back`).
// Points within `epsilon` of the plane go to both parts; an edge that truly crosses the plane gets
// a new vertex `split(a, b, t)` (t = fraction from a to b), whose position is then put exactly on
// the plane. `front` and `back` are appended to; a side with fewer than 3 points is no winding.
template <class Vertex, class Split, class PositionOf = PointPosition>
void clipWindingAxial(const std::vector<Vertex>& w, int axis, float dist, float epsilon, std::vector<Vertex>& front,
                      std::vector<Vertex>& back, Split split, PositionOf positionOf = {}) {
    const size_t n = w.size();
    for (size_t i = 0; i < n; ++i) {
        const Vertex& a = w[i];
        const Vertex& b = w[(i + 1) % n];
        const float da = positionOf(a)[axis] - dist;
        const float db = positionOf(b)[axis] - dist;
        if (da >= -epsilon) front.push_back(a);
        if (da <= epsilon) back.push_back(a);
        const bool crosses = (da > epsilon && db < -epsilon) || (da < -epsilon && db > epsilon);
        if (crosses) {
            Vertex mid = split(a, b, da / (da - db));
            positionOf(mid)[axis] = dist;
            front.push_back(mid);
            back.push_back(mid);
        }
    }
}

// clipWindingAxial for windings of plain points.
inline void clipWindingAxial(const std::vector<Vec3>& w, int axis, float dist, float epsilon, std::vector<Vec3>& front,
                             std::vector<Vec3>& back) {
    clipWindingAxial(w, axis, dist, epsilon, front, back, [](Vec3 a, Vec3 b, float t) { return lerp(a, b, t); });
}

}  // namespace q3::light
