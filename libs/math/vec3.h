// Small fixed-size vector math shared by every stage. Pure functions, no state.
#pragma once

#include <algorithm>
#include <cmath>

namespace q3 {

struct Vec3 {
    float x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    static constexpr Vec3 fromArray(const float* a) { return {a[0], a[1], a[2]}; }
    static constexpr Vec3 splat(float v) { return {v, v, v}; }

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    void toArray(float* a) const { a[0] = x; a[1] = y; a[2] = z; }

    constexpr Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator*(Vec3 o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3 operator/(Vec3 o) const { return {x / o.x, y / o.y, z / o.z}; }
    constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3& operator+=(Vec3 o) { x += o.x; y += o.y; z += o.z; return *this; }
    constexpr Vec3& operator-=(Vec3 o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    constexpr Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
    constexpr Vec3& operator*=(Vec3 o) { x *= o.x; y *= o.y; z *= o.z; return *this; }
    constexpr bool operator==(const Vec3&) const = default;
};

constexpr Vec3 operator*(float s, Vec3 v) { return v * s; }
constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 v) { return std::sqrt(dot(v, v)); }
inline float distance(Vec3 a, Vec3 b) { return length(a - b); }
// Returns v scaled to unit length; the zero vector stays zero.
inline Vec3 normalize(Vec3 v) {
    float len = length(v);
    return len > 0 ? v / len : Vec3{};
}
constexpr Vec3 vmin(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
constexpr Vec3 vmax(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
constexpr float maxComponent(Vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }
constexpr Vec3 lerp(Vec3 a, Vec3 b, float t) { return a + (b - a) * t; }
inline bool isFinite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Axis-aligned box; starts empty so that the first add() defines it.
struct Bounds {
    Vec3 mins{1e30f, 1e30f, 1e30f};
    Vec3 maxs{-1e30f, -1e30f, -1e30f};

    constexpr bool empty() const { return mins.x > maxs.x || mins.y > maxs.y || mins.z > maxs.z; }
    constexpr void add(Vec3 p) { mins = vmin(mins, p); maxs = vmax(maxs, p); }
    constexpr void add(const Bounds& b) { if (!b.empty()) { add(b.mins); add(b.maxs); } }
    constexpr Vec3 center() const { return (mins + maxs) * 0.5f; }
    constexpr Vec3 size() const { return maxs - mins; }
    constexpr bool contains(Vec3 p) const {
        return p.x >= mins.x && p.x <= maxs.x && p.y >= mins.y && p.y <= maxs.y && p.z >= mins.z && p.z <= maxs.z;
    }
    constexpr bool intersects(const Bounds& b) const {
        return mins.x <= b.maxs.x && maxs.x >= b.mins.x && mins.y <= b.maxs.y && maxs.y >= b.mins.y &&
               mins.z <= b.maxs.z && maxs.z >= b.mins.z;
    }
};

constexpr float kPi = 3.14159265358979323846f;
constexpr double kPiD = 3.14159265358979323846;
inline float degToRad(float d) { return d * (kPi / 180.0f); }

}  // namespace q3
