#include "vis_geometry.h"

#include <cmath>

namespace q3::vis {

bool planeFromPoints(Plane& plane, Vec3 a, Vec3 b, Vec3 c) {
    Vec3 n = cross(c - a, b - a);
    float len = length(n);
    if (len == 0) return false;
    n = n / len;
    plane = {n, dot(a, n)};
    return true;
}

const Winding* chopWinding(const Winding* in, const Plane& split, Winding* out) {
    enum Side : unsigned char { Front, Back, On };
    std::array<float, kMaxWindingPoints + 1> dists;
    std::array<Side, kMaxWindingPoints + 1> sides;
    int front = 0, back = 0;
    const int n = in->count;
    for (int i = 0; i < n; ++i) {
        dists[i] = split.distanceTo(in->points[i]);
        if (dists[i] > kOnEpsilon) {
            sides[i] = Front;
            ++front;
        } else if (dists[i] < -kOnEpsilon) {
            sides[i] = Back;
            ++back;
        } else {
            sides[i] = On;
        }
    }
    if (back == 0) return in;
    if (front == 0) return nullptr;
    sides[n] = sides[0];
    dists[n] = dists[0];

    out->count = 0;
    for (int i = 0; i < n; ++i) {
        const Vec3 p1 = in->points[i];
        if (out->count == kMaxWindingPoints) return in;
        if (sides[i] == On) {
            out->points[out->count++] = p1;
            continue;
        }
        if (sides[i] == Front) out->points[out->count++] = p1;
        if (sides[i + 1] == On || sides[i + 1] == sides[i]) continue;
        if (out->count == kMaxWindingPoints) return in;
        const Vec3 p2 = in->points[(i + 1) % n];
        const float t = dists[i] / (dists[i] - dists[i + 1]);
        Vec3 mid;
        for (int j = 0; j < 3; ++j) {
            // Exact coordinates on axial planes avoid round-off.
            if (split.normal[j] == 1)
                mid[j] = split.dist;
            else if (split.normal[j] == -1)
                mid[j] = -split.dist;
            else
                mid[j] = p1[j] + t * (p2[j] - p1[j]);
        }
        out->points[out->count++] = mid;
    }
    return out;
}

bool findSeparator(const Winding& source, const Winding& pass, int edge, bool flip, Plane& out) {
    // Side tests run on the unnormalised normal against the epsilon scaled by its length
    // (squared, so no square root until a separator is found).
    constexpr float kEpsilonSq = kOnEpsilon * kOnEpsilon;
    const int i = edge;
    const int l = (i + 1) % source.count;
    const Vec3 a = source.points[i];
    const Vec3 edgeVector = source.points[l] - a;
    for (int j = 0; j < pass.count; ++j) {
        // The plane through a, pass[j], source[l] as planeFromPoints orients it.
        Vec3 normal = cross(edgeVector, pass.points[j] - a);
        const float lengthSq = dot(normal, normal);
        if (lengthSq == 0) continue;
        const float limitSq = kEpsilonSq * lengthSq;
        auto beyond = [&](float d) { return d * d > limitSq; };
        // Which side holds the source portal: the plane is turned so that source is behind.
        bool sourceInFront = false;
        int k = 0;
        for (; k < source.count; ++k) {
            if (k == i || k == l) continue;
            const float d = dot(normal, source.points[k] - a);
            if (!beyond(d)) continue;
            sourceInFront = d > 0;
            break;
        }
        if (k == source.count) continue;  // coplanar with the source portal
        if (sourceInFront) normal = -normal;
        // A separator has every point of pass on or in front of it, one strictly.
        int inFront = 0;
        for (k = 0; k < pass.count; ++k) {
            if (k == j) continue;
            const float d = dot(normal, pass.points[k] - a);
            if (!beyond(d)) continue;
            if (d < 0) break;
            ++inFront;
        }
        if (k != pass.count || inFront == 0) continue;
        normal = normal / std::sqrt(lengthSq);
        const Plane plane{normal, dot(a, normal)};
        out = flip ? plane.flipped() : plane;
        return true;
    }
    return false;
}

int findSeparators(const Winding& source, const Winding& pass, bool flip, Plane* out) {
    int found = 0;
    for (int i = 0; i < source.count; ++i)
        if (findSeparator(source, pass, i, flip, out[found])) ++found;
    return found;
}

void boundingSphere(const Winding& w, Vec3& origin, float& radius) {
    Vec3 sum;
    for (Vec3 p : w.view()) sum += p;
    origin = sum / static_cast<float>(w.count);
    double best = 0;
    for (Vec3 p : w.view()) best = std::max(best, static_cast<double>(length(p - origin)));
    radius = static_cast<float>(best);
}

}  // namespace q3::vis
