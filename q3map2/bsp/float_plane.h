// Planes in 32-bit floats, built the way q3map2's Plane3f PlaneFromPoints builds them, for steps
// whose output depends on float rounding (misc_model clip brushes, decal projectors).
#pragma once

#include <cmath>

#include "vec3.h"

namespace q3::bspstage {

struct FPlane {
    Vec3 normal;
    float dist = 0;

    float distanceTo(Vec3 p) const { return dot(normal, p) - dist; }
};

// q3map2's VectorNormalize: the length and the division in doubles.
inline Vec3 normalizedLikeQ3map2(const Vec3& v, double* lengthOut = nullptr) {
    const double x = v.x, y = v.y, z = v.z, len = std::sqrt(x * x + y * y + z * z);
    if (lengthOut) *lengthOut = len;
    if (len == 0) return {0, 0, 0};
    return {float(x / len), float(y / len), float(z / len)};
}

// Normal (c - a) x (b - a), normalised; false (dist 0) for collinear or coincident points.
inline bool floatPlaneFromPoints(FPlane& plane, const Vec3& a, const Vec3& b, const Vec3& c) {
    double len = 0;
    plane.normal = normalizedLikeQ3map2(cross(c - a, b - a), &len);
    if (len == 0) {
        plane.dist = 0;
        return false;
    }
    plane.dist = dot(a, plane.normal);
    return true;
}

}  // namespace q3::bspstage
