#include "lightmap_layout_mapping.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>

namespace q3::light {
namespace {

constexpr float kSplitThreshold = 1.0f;  // squared edge length (super luxels) below which splitting stops
constexpr float kAxialEpsilon = 0.01f;   // an edge this close to a lightmap axis counts as axial
constexpr float kQuadFlatness = 0.5f;    // the fourth point of a flat quad lies this close to its plane

// `sameNormal`: both normals are one vector that normalize() leaves unchanged, so the midpoint's
// normal is that vector bit for bit (normalize(n + n) scales by exact powers of two) and needs no
// square root.
template <bool sameNormal>
MapVertex midpoint(const MapVertex& a, const MapVertex& b) {
    return {{(a.st[0] + b.st[0]) * 0.5f, (a.st[1] + b.st[1]) * 0.5f}, (a.xyz + b.xyz) * 0.5f,
            sameNormal ? a.normal : normalize(a.normal + b.normal)};
}

// Whether every corner has the same normal and it is a fixed point of normalize().
template <size_t N>
bool sharesFixedNormal(const std::array<MapVertex, N>& corners) {
    const Vec3 n = corners[0].normal;
    for (const MapVertex& v : corners)
        if (!(v.normal == n)) return false;
    return normalize(n) == n;
}

float squaredStDistance(const MapVertex& a, const MapVertex& b) {
    const float ds = a.st[0] - b.st[0], dt = a.st[1] - b.st[1];
    return ds * ds + dt * dt;
}

// The plane a primitive is mapped with: the lightmap's own plane when it has one, else the plane
// through the first three points (facing like their normals); false when degenerate.
bool primitivePlane(const RawLightmap& lm, const MapVertex& a, const MapVertex& b, const MapVertex& c, Vec3& normal,
                    float& dist) {
    if (lm.planar) {
        normal = lm.planeNormal;
        dist = lm.planeDist;
    } else {
        normal = cross(c.xyz - a.xyz, b.xyz - a.xyz);
        if (dot(normal, normal) < 1e-12f) return false;
        normal = normalize(normal);
        if (dot(normal, a.normal + b.normal + c.normal) < 0.0f) normal = -normal;
        dist = dot(a.xyz, normal);
    }
    // A projected lightmap cannot place luxels on a plane parallel to its axis.
    return lm.axisNum < 0 || normal[lm.axisNum] != 0.0f;
}

// Whether every vertex of every surface has one normal along an axis. Summing that normal any
// number of times and normalizing gives it back exactly, so the luxels' normals need no sums, and a
// split whose points can only fall on luxels already mapped changes nothing.
bool sharesAxialNormal(std::span<const MappingSurface> surfaces) {
    std::optional<Vec3> shared;
    for (const MappingSurface& s : surfaces)
        for (const MapVertex& v : s.verts) {
            if (!shared) {
                const Vec3 n = v.normal;
                const int zeros = int(n.x == 0.0f) + int(n.y == 0.0f) + int(n.z == 0.0f);
                if (zeros != 2 || std::fabs(n.x + n.y + n.z) != 1.0f) return false;
                shared = n;
            } else if (std::bit_cast<std::array<uint32_t, 3>>(v.normal) !=
                       std::bit_cast<std::array<uint32_t, 3>>(*shared)) {  // zeros of one sign too
                return false;
            }
        }
    return shared.has_value();
}

class LuxelMapper {
public:
    LuxelMapper(RawLightmap& lm, bool sharedAxialNormal)
        : lm_(lm),
          sharedAxialNormal_(sharedAxialNormal),
          normalSums_(sharedAxialNormal ? 0 : lm.luxels.size()),
          mapped_(lm.luxels.size(), 0) {}

    void mapSurface(const MappingSurface& s) {
        if (s.quadWidth >= 2 && s.quadHeight >= 2 && s.verts.size() == size_t(s.quadWidth) * size_t(s.quadHeight)) {
            mapQuadMesh(s);
            return;
        }
        for (int nonAxial = 0; nonAxial < 2; ++nonAxial)
            for (size_t i = 0; i + 2 < s.triangles.size(); i += 3) {
                const uint32_t a = s.triangles[i], b = s.triangles[i + 1], c = s.triangles[i + 2];
                if (a >= s.verts.size() || b >= s.verts.size() || c >= s.verts.size()) continue;
                mapTriangle({s.verts[a], s.verts[b], s.verts[c]}, nonAxial != 0);
            }
    }

    void finish() {
        for (size_t i = 0; i < normalSums_.size(); ++i)
            if (mapped_[i] && dot(normalSums_[i], normalSums_[i]) > 0.0f)
                lm_.luxels[i].normal = normalize(normalSums_[i]);
    }

private:
    using Tri = std::array<MapVertex, 3>;
    using Quad = std::array<MapVertex, 4>;

    void mapPoint(const MapVertex& v, Vec3 planeNormal, float planeDist) {
        const int sw = lm_.superWidth(), sh = lm_.superHeight();
        const int x = std::clamp(int(v.st[0]), 0, sw - 1), y = std::clamp(int(v.st[1]), 0, sh - 1);
        const size_t i = size_t(y) * size_t(sw) + size_t(x);
        if (!sharedAxialNormal_) normalSums_[i] += v.normal;
        if (mapped_[i]) return;
        mapped_[i] = 1;
        Luxel& l = lm_.luxels[i];
        Vec3 origin = v.xyz;
        if (lm_.axisNum >= 0) {
            const float S = float(lm_.superSample);
            const float s = (float(x) + 0.5f) / S - 0.5f, t = (float(y) + 0.5f) / S - 0.5f;
            origin = lm_.origin + lm_.vecs[0] * s + lm_.vecs[1] * t;
            origin[lm_.axisNum] -= (dot(origin, planeNormal) - planeDist) / planeNormal[lm_.axisNum];
            origin[lm_.axisNum] += planeNormal[lm_.axisNum] < 0.0f ? -lm_.sampleOffset : lm_.sampleOffset;
        } else {
            origin += planeNormal * lm_.sampleOffset;
        }
        l.origin = origin;
        l.normal = v.normal;
        l.mapped = true;
        l.surfacePoint = v.xyz;
        l.surfaceNormal = v.normal;
        l.faceNormal = planeNormal;
    }

    // The polygon's longest edge in lightmap space (edge i runs from corner i to i + 1), or -1 when
    // every edge is already within one super luxel.
    template <size_t N>
    static int longestEdgeToSplit(const std::array<MapVertex, N>& corners) {
        int longest = -1;
        float longestDist = kSplitThreshold;
        for (size_t i = 0; i < N; ++i) {
            const float dist = squaredStDistance(corners[i], corners[(i + 1) % N]);
            if (dist > longestDist) longestDist = dist, longest = int(i);
        }
        return longest;
    }

    // Splits the longest edge until every edge is at most one super luxel, mapping each midpoint.
    void splitTriangle(const Tri& tri, Vec3 n, float d) {
        if (sharesFixedNormal(tri)) splitTriangleAs<true>(tri, n, d);
        else splitTriangleAs<false>(tri, n, d);
    }
    // The corners by address: each half shares two of them with its parent, so only the midpoint
    // is new (copying whole triangles was most of the cost of a split).
    template <bool sameNormal>
    void splitTriangleAs(const Tri& tri, Vec3 n, float d) {
        splitCornersAs<sameNormal>({&tri[0], &tri[1], &tri[2]}, n, d);
    }
    template <bool sameNormal>
    void splitCornersAs(const std::array<const MapVertex*, 3>& corners, Vec3 n, float d) {
        int longest = -1;
        float longestDist = kSplitThreshold;
        for (size_t i = 0; i < 3; ++i) {
            const float dist = squaredStDistance(*corners[i], *corners[(i + 1) % 3]);
            if (dist > longestDist) longestDist = dist, longest = int(i);
        }
        if (longest < 0 || (sameNormal && sharedAxialNormal_ && coversOnlyMapped(corners))) return;
        const size_t a = size_t(longest), b = (a + 1) % 3;
        const MapVertex mid = midpoint<sameNormal>(*corners[a], *corners[b]);
        mapPoint(mid, n, d);
        std::array<const MapVertex*, 3> half = corners;
        half[a] = &mid;
        splitCornersAs<sameNormal>(half, n, d);
        half[a] = corners[a];
        half[b] = &mid;
        splitCornersAs<sameNormal>(half, n, d);
    }

    // Whether every luxel a point inside the triangle can map to (mapPoint's truncation and clamp
    // of its box's corners) is mapped already; false without looking when that is more than 16 x 16.
    bool coversOnlyMapped(const std::array<const MapVertex*, 3>& corners) const {
        const std::array<float, 2>& s0 = corners[0]->st;
        const std::array<float, 2>& s1 = corners[1]->st;
        const std::array<float, 2>& s2 = corners[2]->st;
        const int sw = lm_.superWidth(), sh = lm_.superHeight();
        const int x0 = std::clamp(int(std::min({s0[0], s1[0], s2[0]})), 0, sw - 1);
        const int x1 = std::clamp(int(std::max({s0[0], s1[0], s2[0]})), 0, sw - 1);
        const int y0 = std::clamp(int(std::min({s0[1], s1[1], s2[1]})), 0, sh - 1);
        const int y1 = std::clamp(int(std::max({s0[1], s1[1], s2[1]})), 0, sh - 1);
        if (x1 - x0 > 15 || y1 - y0 > 15) return false;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                if (!mapped_[size_t(y) * size_t(sw) + size_t(x)]) return false;
        return true;
    }

    // The vertices, then either the whole triangle (second pass) or only its axial edges (first
    // pass, so that edges along the luxel grid claim their luxels before diagonal ones).
    void mapTriangle(const Tri& tri, bool nonAxial) {
        Vec3 n;
        float d;
        if (!primitivePlane(lm_, tri[0], tri[1], tri[2], n, d)) return;
        for (const MapVertex& v : tri) mapPoint(v, n, d);
        if (nonAxial) {
            splitTriangle(tri, n, d);
            return;
        }
        for (int i = 0; i < 3; ++i) {
            const MapVertex& a = tri[size_t(i)];
            const MapVertex& b = tri[size_t((i + 1) % 3)];
            if (std::fabs(a.st[0] - b.st[0]) <= kAxialEpsilon || std::fabs(a.st[1] - b.st[1]) <= kAxialEpsilon)
                splitTriangle({a, b, b}, n, d);
        }
    }

    void splitQuad(const Quad& q, Vec3 n, float d) {
        if (sharesFixedNormal(q)) splitQuadAs<true>(q, n, d);
        else splitQuadAs<false>(q, n, d);
    }
    template <bool sameNormal>
    void splitQuadAs(const Quad& q, Vec3 n, float d) {
        const int longest = longestEdgeToSplit(q);
        if (longest < 0) return;
        const int e = longest & 1;  // split both opposite edges of the pair
        const MapVertex m0 = midpoint<sameNormal>(q[size_t(e)], q[size_t(e + 1)]);
        const MapVertex m1 = midpoint<sameNormal>(q[size_t(e + 2)], q[size_t((e + 3) % 4)]);
        mapPoint(m0, n, d);
        mapPoint(m1, n, d);
        if (e == 0) {
            splitQuadAs<sameNormal>({q[0], m0, m1, q[3]}, n, d);
            splitQuadAs<sameNormal>({m0, q[1], q[2], m1}, n, d);
        } else {
            splitQuadAs<sameNormal>({q[0], q[1], m0, m1}, n, d);
            splitQuadAs<sameNormal>({m1, m0, q[2], q[3]}, n, d);
        }
    }

    bool mapQuad(const Quad& q) {
        Vec3 n;
        float d;
        if (!primitivePlane(lm_, q[0], q[1], q[2], n, d)) return false;
        if (std::fabs(dot(q[3].xyz, n) - d) > kQuadFlatness) return false;
        for (const MapVertex& v : q) mapPoint(v, n, d);
        splitQuad(q, n, d);
        return true;
    }

    void mapQuadMesh(const MappingSurface& s) {
        const int w = s.quadWidth;
        for (int y = 0; y + 1 < s.quadHeight; ++y)
            for (int x = 0; x + 1 < w; ++x) {
                // Corners counter-clockwise from (x, y), the diagonal alternating as q3map2's (x + y) & 1.
                const size_t pw[5] = {size_t(y * w + x), size_t((y + 1) * w + x), size_t((y + 1) * w + x + 1),
                                      size_t(y * w + x + 1), size_t(y * w + x)};
                const size_t r = size_t((x + y) & 1);
                const MapVertex& a = s.verts[pw[r]];
                const MapVertex& b = s.verts[pw[r + 1]];
                const MapVertex& c = s.verts[pw[r + 2]];
                const MapVertex& e = s.verts[pw[r + 3]];
                if (mapQuad({a, b, c, e})) continue;
                for (int nonAxial = 0; nonAxial < 2; ++nonAxial) {
                    mapTriangle({a, b, c}, nonAxial != 0);
                    mapTriangle({a, c, e}, nonAxial != 0);
                }
            }
    }

    RawLightmap& lm_;
    bool sharedAxialNormal_;
    std::vector<Vec3> normalSums_;  // empty with a shared axial normal
    // Luxel::mapped packed one byte a luxel: the splits ask it for every midpoint and whole boxes.
    std::vector<uint8_t> mapped_;
};

}  // namespace

void mapSurfacesOntoLuxels(RawLightmap& lm, std::span<const MappingSurface> surfaces) {
    lm.luxels.assign(size_t(lm.superWidth()) * size_t(lm.superHeight()), Luxel{});
    if (lm.luxels.empty()) return;
    LuxelMapper mapper(lm, sharesAxialNormal(surfaces));
    for (const MappingSurface& s : surfaces) mapper.mapSurface(s);
    mapper.finish();
}

}  // namespace q3::light
