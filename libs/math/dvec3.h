// Double-precision vectors and planes for geometry that must not pick up float noise (the BSP
// stage: brush windings, splits, portals). Pure functions, no state.
#pragma once

#include <algorithm>
#include <cmath>

#include "vec3.h"

namespace q3 {

struct DVec3 {
    double x = 0, y = 0, z = 0;

    constexpr DVec3() = default;
    constexpr DVec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit DVec3(Vec3 v) : x(v.x), y(v.y), z(v.z) {}
    static constexpr DVec3 splat(double v) { return {v, v, v}; }
    static constexpr DVec3 axis(int i, double sign = 1) {
        return {i == 0 ? sign : 0.0, i == 1 ? sign : 0.0, i == 2 ? sign : 0.0};
    }

    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    Vec3 toFloat() const { return {float(x), float(y), float(z)}; }

    constexpr DVec3 operator+(DVec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr DVec3 operator-(DVec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr DVec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr DVec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    constexpr DVec3 operator-() const { return {-x, -y, -z}; }
    constexpr DVec3& operator+=(DVec3 o) { x += o.x; y += o.y; z += o.z; return *this; }
    constexpr DVec3& operator-=(DVec3 o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    constexpr DVec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
    constexpr bool operator==(const DVec3&) const = default;
};

constexpr DVec3 operator*(double s, DVec3 v) { return v * s; }
constexpr double dot(DVec3 a, DVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr DVec3 cross(DVec3 a, DVec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(DVec3 v) { return std::sqrt(dot(v, v)); }
// Returns v scaled to unit length; the zero vector stays zero.
inline DVec3 normalize(DVec3 v) {
    double len = length(v);
    return len > 0 ? v / len : DVec3{};
}
constexpr DVec3 vmin(DVec3 a, DVec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
constexpr DVec3 vmax(DVec3 a, DVec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
// Every component of `a` within `epsilon` of `b`'s.
inline bool nearlyEqual(DVec3 a, DVec3 b, double epsilon) {
    return std::fabs(a.x - b.x) <= epsilon && std::fabs(a.y - b.y) <= epsilon && std::fabs(a.z - b.z) <= epsilon;
}
// The value q3map2 would have stored in a 32-bit float.
inline DVec3 roundToFloat(DVec3 v) { return {double(float(v.x)), double(float(v.y)), double(float(v.z))}; }

// Axis-aligned box; starts empty so that the first add() defines it.
struct DBounds {
    DVec3 mins{1e300, 1e300, 1e300};
    DVec3 maxs{-1e300, -1e300, -1e300};

    constexpr bool empty() const { return mins.x > maxs.x || mins.y > maxs.y || mins.z > maxs.z; }
    constexpr void add(DVec3 p) { mins = vmin(mins, p); maxs = vmax(maxs, p); }
    constexpr void add(const DBounds& b) { if (!b.empty()) { add(b.mins); add(b.maxs); } }
    constexpr DVec3 center() const { return (mins + maxs) * 0.5; }
    constexpr bool intersects(const DBounds& b) const {
        return mins.x <= b.maxs.x && maxs.x >= b.mins.x && mins.y <= b.maxs.y && maxs.y >= b.mins.y &&
               mins.z <= b.maxs.z && maxs.z >= b.mins.z;
    }
    // True when `b` lies strictly inside this box.
    constexpr bool surroundsStrictly(const DBounds& b) const {
        return b.mins.x > mins.x && b.mins.y > mins.y && b.mins.z > mins.z && b.maxs.x < maxs.x &&
               b.maxs.y < maxs.y && b.maxs.z < maxs.z;
    }
};

// normal . p = dist; the normal is unit length.
struct DPlane {
    DVec3 normal;
    double dist = 0;

    constexpr DPlane flipped() const { return {-normal, -dist}; }
    constexpr double distanceTo(DVec3 p) const { return dot(normal, p) - dist; }
};

}  // namespace q3
