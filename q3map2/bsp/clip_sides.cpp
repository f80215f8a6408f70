#include "clip_sides.h"

#include <algorithm>
#include <cmath>

#include "model_clip.h"

namespace q3::bspstage {
namespace {

double minAngleSquaredSin(const DVec3& a, const DVec3& b, const DVec3& c) {
    const DVec3 d[3] = {b - a, c - a, c - b};
    const double l[3] = {dot(d[0], d[0]), dot(d[1], d[1]), dot(d[2], d[2])};
    const int mini = l[0] < l[1] ? (l[0] < l[2] ? 0 : 2) : (l[1] < l[2] ? 1 : 2);
    if (l[mini] == 0) return 0;
    const int minj = mini == 2 ? 0 : mini + 1, mink = minj == 2 ? 0 : minj + 1;
    const DVec3 x = cross(d[minj], d[mink]);
    return dot(x, x) / (l[minj] * l[mink]);
}

// Area-weighted centre of a convex polygon.
DVec3 centroid(const std::vector<DVec3>& w) {
    DVec3 sum{0, 0, 0};
    double total = 0;
    for (size_t i = 2; i < w.size(); ++i) {
        const double area = 0.5 * length(cross(w[i - 1] - w[0], w[i] - w[0]));
        sum += (w[0] + w[i - 1] + w[i]) * (area / 3.0);
        total += area;
    }
    return total > 0 ? sum / total : w[0];
}

DVec3 floatRounded(const DVec3& v) { return roundToFloat(v); }

// q3map2's plane snapping on a float plane (normal renormalised and distance re-derived through the
// points' centre in floats; axial distances near an integer rounded). True when the plane moved.
bool snapFloatPlane(DPlane& p, std::span<const DVec3> points, const PlaneEpsilons& epsilons) {
    const DPlane before = p;
    DVec3 n = p.normal;
    if (snapNormal(n, epsilons.normal)) {
        p.normal = floatRounded(n);
        if (!points.empty()) {
            DVec3 centre{0, 0, 0};
            for (const DVec3& q : points) centre += q;
            p.dist = float(dot(p.normal, centre / double(points.size())));
        }
    }
    const int zeros = int(p.normal.x == 0) + int(p.normal.y == 0) + int(p.normal.z == 0);
    if (zeros > 1) {
        const double nearest = std::rint(float(p.dist));
        if (-epsilons.distance < p.dist - nearest && p.dist - nearest < epsilons.distance) p.dist = nearest;
    }
    return p.normal != before.normal || p.dist != before.dist;
}

}  // namespace

DVec3 axialOf(const DVec3& n, int* axisOut) {
    int axis = 0;
    for (int i = 1; i < 3; ++i)
        if (std::fabs(n[i]) > std::fabs(n[axis])) axis = i;
    DVec3 out{0, 0, 0};
    out[axis] = n[axis] >= 0 ? 1 : -1;
    if (axisOut) *axisOut = axis;
    return out;
}

bool ClipSides::construct(const PlaneEpsilons& epsilons) {
    auto perimeter = [&](size_t a, size_t b, size_t c) {
        const DVec3 ab = points[b] - points[a], ac = points[a] - points[c], bc = points[c] - points[b];
        return dot(ab, ab) + dot(ac, ac) + dot(bc, bc);
    };
    size_t a = 0, b = 1, c = 2;
    while (c + 1 < points.size() && perimeter(a, b, c + 1) > perimeter(a, b, c)) ++c;
    while (b + 1 != c && perimeter(a, b + 1, c) > perimeter(a, b, c)) ++b;
    // A float plane: the cross product rounded to floats, normalised in doubles.
    const DVec3 n = floatRounded(cross(points[c] - points[a], points[b] - points[a]));
    if (length(n) == 0) return false;
    front.normal = floatRounded(n / length(n));
    front.dist = float(dot(points[a], front.normal));
    if (snapFloatPlane(front, points, epsilons))
        for (DVec3& p : points) p = p - front.normal * front.distanceTo(p);
    sides.assign(points.size(), DPlane{});
    return minAngleSquaredSin(points[a], points[b], points[c]) >= 1e-8;
}

void ClipSides::sidesAlong(const DVec3& direction) {
    for (size_t i = 0; i < points.size(); ++i) {
        sides[i].normal = normalize(cross(direction, next(i) - points[i]));
        sides[i].dist = dot(points[i], sides[i].normal);
    }
}

void ClipSides::addBack(const DVec3& direction) {
    hasBack = true;
    back = front.flipped();
    back.dist += dot(direction, front.normal) * clipDepth;
    back = {floatRounded(back.normal), double(float(back.dist))};
    backPoints = points;
    for (DVec3& p : backPoints) p -= direction * clipDepth;
}

void ClipSides::defaultShape() {
    const DVec3 axis = axialOf(front.normal);
    sidesAlong(axis);
    addBack(axis);
}

void ClipSides::pyramid() {
    const DVec3 apex = centroid(points) - front.normal * clipDepth;
    for (size_t i = 0; i < points.size(); ++i) {
        const DVec3& a = next(i);
        const DVec3 n = cross(apex - a, points[i] - a);
        sides[i].normal = normalize(n);
        sides[i].dist = dot(a, sides[i].normal);
    }
}

void ClipSides::faceNormals() {
    sidesAlong(front.normal);
    addBack(front.normal);
}

void ClipSides::leaning45() {
    for (size_t i = 0; i < points.size(); ++i) {
        const DVec3 out = normalize(cross(front.normal, next(i) - points[i]));
        sides[i].normal = normalize(out - front.normal);
        sides[i].dist = dot(points[i], sides[i].normal);
    }
    addBack(front.normal);
}

void ClipSides::extruded(const DVec3& direction) {
    if (dot(front.normal, direction) < 0.05) return defaultShape();
    sidesAlong(direction);
    addBack(direction);
}

void ClipSides::axialPyramid(float limitDepth) {
    for (int i = 0; i < 3; ++i)
        if (std::fabs(front.normal[i]) < 0.05 && std::fabs(front.normal[(i + 1) % 3]) < 0.05) return defaultShape();
    int axis = 0;
    const DVec3 best = axialOf(front.normal, &axis);
    float minDist = 999999;
    for (size_t i = 0; i < points.size(); ++i) {
        float bestDist = 999999, bestAngle = 1;
        const DVec3 edge = normalize(next(i) - points[i]);
        for (int ax = 0; ax < 3; ++ax) {
            DPlane p;
            if (ax == axis) {
                p.normal = normalize(cross(best, edge));
            } else {
                if (std::fabs(edge[ax]) < 0.00025) continue;
                DVec3 n{0, 0, 0};
                n[ax] = edge[ax];
                p.normal = normalize(cross(cross(best, n), edge));
            }
            p.dist = dot(points[i], p.normal);
            const float thickness = float(-p.distanceTo(points[(i + 2) % points.size()]));
            const float angle = float(dot(p.normal, front.normal));
            if ((thickness > 0.1f && thickness < bestDist && angle < 0) || (angle >= 0 && angle <= bestAngle)) {
                bestAngle = angle;
                if (angle < 0) bestDist = thickness;
                sides[i] = p;
            }
        }
        if (bestDist == 999999 && bestAngle == 1) return defaultShape();
        minDist = std::min(minDist, bestDist);
    }
    if (limitDepth != 0 && minDist > limitDepth) return defaultShape();
}

void ClipSides::vertexNormals(const std::array<Vec3, 3>& normals, bool noOutwardCheck) {
    std::array<DVec3, 3> edgeNormals;
    for (size_t i = 0; i < 3; ++i) {
        const Vec3 sum = normals[i] + normals[(i + 1) % 3];
        edgeNormals[i] = normalize(DVec3(sum));
        const DVec3 out = normalize(cross(front.normal, points[(i + 1) % 3] - points[i]));
        const bool facing = dot(edgeNormals[i], front.normal) > 0.1;
        if (facing && (noOutwardCheck || dot(edgeNormals[i], out) > -0.2)) continue;
        edgeNormals[i] = normalize(front.normal + out);
    }
    for (size_t i = 0; i < 3; ++i) {
        sides[i].normal = normalize(cross(edgeNormals[i], points[(i + 1) % 3] - points[i]));
        sides[i].dist = dot(points[i], sides[i].normal);
    }
    addBack(front.normal);
}

void ClipSides::constructVolume(const DPlane& firstFace) {
    front = {floatRounded(firstFace.normal), double(float(firstFace.dist))};
    sides.assign(points.size(), DPlane{});
}

void ClipSides::specialBack(int shape, const DVec3& direction, const DBounds& bounds, float limitDepth) {
    sidesAlong(direction);
    int axis = 0;
    axialOf(direction, &axis);
    const bool positive = direction[axis] > 0;
    if (shape & clipflag::MaxExtrude) {
        hasBack = true;
        back.normal = -direction;
        back.dist = float(positive ? -bounds.mins[axis] + clipDepth : bounds.maxs[axis] + clipDepth);
        return;
    }
    if (!(shape & clipflag::AxialBackplane)) return;
    // The first corner lowest (or highest) along the axis.
    auto extreme = [&](bool highest) {
        size_t best = 0;
        for (size_t i = 1; i < points.size(); ++i)
            if (highest ? points[i][axis] > points[best][axis] : points[i][axis] < points[best][axis]) best = i;
        return points[best];
    };
    hasBack = true;
    back.normal = -direction;
    back.dist = float(positive ? -extreme(false)[axis] + clipDepth : extreme(true)[axis] + clipDepth);
    if (limitDepth == 0) return;
    DVec3 far = floatRounded(extreme(positive));
    far = far - back.normal * back.distanceTo(far);
    if (-front.distanceTo(far) > limitDepth) addBack(direction);
}

}  // namespace q3::bspstage
