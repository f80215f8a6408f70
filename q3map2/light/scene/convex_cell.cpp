#include "convex_cell.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace q3::light {
namespace {

double planeEpsilon(DVec3 normal, double dist, const DBounds& b) {
    const double extent = std::max({std::fabs(b.mins.x), std::fabs(b.mins.y), std::fabs(b.mins.z),
                                    std::fabs(b.maxs.x), std::fabs(b.maxs.y), std::fabs(b.maxs.z)});
    return 1e-12 * (std::fabs(dist) + length(normal) * extent) + 1e-300;
}

// The part of a convex polygon where dot(normal, x) - dist <= epsilon.
std::vector<DVec3> clipPolygon(const std::vector<DVec3>& points, DVec3 normal, double dist, double epsilon) {
    std::vector<DVec3> out;
    out.reserve(points.size() + 2);
    const size_t n = points.size();
    for (size_t i = 0; i < n; ++i) {
        const DVec3 a = points[i], b = points[(i + 1) % n];
        const double da = dot(normal, a) - dist, db = dot(normal, b) - dist;
        if (da <= epsilon) out.push_back(a);
        if ((da < -epsilon && db > epsilon) || (da > epsilon && db < -epsilon))
            out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

// A square on the plane around `center`'s projection, `half` from its middle to each side.
std::vector<DVec3> squareOnPlane(DVec3 normal, double dist, DVec3 center, double half) {
    const DVec3 n = normalize(normal);
    const double d = dist / length(normal);
    const DVec3 origin = center - n * (dot(n, center) - d);
    const DVec3 helper = std::fabs(n.z) < 0.9 ? DVec3{0, 0, 1} : DVec3{1, 0, 0};
    const DVec3 u = normalize(cross(helper, n)) * half;
    const DVec3 v = cross(n, normalize(u)) * half;
    return {origin - u - v, origin + u - v, origin + u + v, origin - u + v};
}

}  // namespace

ConvexCell ConvexCell::box(DVec3 lo, DVec3 hi) {
    ConvexCell cell;
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return cell;
    for (int axis = 0; axis < 3; ++axis)
        for (const double sign : {1.0, -1.0}) {
            const DVec3 normal = DVec3::axis(axis, sign);
            const double dist = sign > 0 ? hi[axis] : -lo[axis];
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            Face f{{normal, dist}, {}};
            for (const auto& [sa, sb] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{1, 1}, std::pair{0, 1}}) {
                DVec3 p;
                p[axis] = sign > 0 ? hi[axis] : lo[axis];
                p[a] = sa ? hi[a] : lo[a];
                p[b] = sb ? hi[b] : lo[b];
                f.points.push_back(p);
            }
            cell.faces_.push_back(std::move(f));
        }
    return cell;
}

DBounds ConvexCell::bounds() const {
    DBounds b;
    for (const Face& f : faces_)
        for (const DVec3& p : f.points) b.add(p);
    return b;
}

std::vector<ConvexCell::Plane> ConvexCell::planes() const {
    std::vector<Plane> out;
    out.reserve(faces_.size());
    for (const Face& f : faces_) out.push_back(f.plane);
    return out;
}

bool ConvexCell::inside(DVec3 normal, double dist) const {
    const double epsilon = planeEpsilon(normal, dist, bounds());
    for (const Face& f : faces_)
        for (const DVec3& p : f.points)
            if (dot(normal, p) - dist > epsilon) return false;
    return true;
}

ConvexCell ConvexCell::clipped(DVec3 normal, double dist) const {
    const DBounds b = bounds();
    const double epsilon = planeEpsilon(normal, dist, b);
    ConvexCell out;
    for (const Face& f : faces_) {
        std::vector<DVec3> points = clipPolygon(f.points, normal, dist, epsilon);
        if (points.size() >= 3) out.faces_.push_back(Face{f.plane, std::move(points)});
    }
    if (out.faces_.empty()) return out;
    // The new face: the plane's square around the cell, cut by every face plane of the cell.
    const double half = 2.0 * length(b.maxs - b.mins) + 1.0;
    std::vector<DVec3> cap = squareOnPlane(normal, dist, b.center(), half);
    for (const Face& f : faces_) {
        cap = clipPolygon(cap, f.plane.normal, f.plane.dist, planeEpsilon(f.plane.normal, f.plane.dist, b));
        if (cap.size() < 3) break;
    }
    if (cap.size() >= 3) out.faces_.push_back(Face{{normal, dist}, std::move(cap)});
    return out;
}

}  // namespace q3::light
