#include "form_factor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "angle.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace q3::light {
namespace {

// |total| past this (beyond 2 pi) means the polygon is numerically broken: q3map2 gives up on it.
constexpr double kBrokenTotal = 6.3;

// One edge's share before the double-precision sum: the cosine term (dot(normal, c) / sine) and
// the edge's angle; `counts` false for an edge seen end-on (sine of its angle below 1e-4).
struct EdgeTerm {
    float cosine = 0, angle = 0;
    bool counts = false;
};

EdgeTerm edgeTerm(Vec3 normal, Vec3 a, float a2, Vec3 b, float b2) {
    const Vec3 c = cross(a, b);
    const float c2 = dot(c, c);
    if (!(c2 >= 1e-8f * a2 * b2 && c2 > 0)) return {};
    const float sine = std::sqrt(c2);
    return {dot(normal, c) / sine, atan2NonNegative(sine, dot(a, b)), true};
}

// Adds one edge to the running total; false when the total shows a broken polygon.
bool addEdge(double& total, const EdgeTerm& e) {
    if (!e.counts) return true;
    total += static_cast<double>(e.cosine) * static_cast<double>(e.angle);
    return !(total > kBrokenTotal || total < -kBrokenTotal);
}

#if defined(__SSE2__)
constexpr size_t kMaxVectorCorners = 64;

// Four edges at once: lanes of their start offsets a (x, y, z, |a|^2) and end offsets b.
struct EdgeLanes {
    __m128 ax, ay, az, a2, bx, by, bz, b2;
};

// Each lane's EdgeTerm (cosine, angle, counts), in Vec3's order of operations.
void edgeTerms4(Vec3 normal, const EdgeLanes& e, EdgeTerm out[4]) {
    const __m128 cx = _mm_sub_ps(_mm_mul_ps(e.ay, e.bz), _mm_mul_ps(e.az, e.by));
    const __m128 cy = _mm_sub_ps(_mm_mul_ps(e.az, e.bx), _mm_mul_ps(e.ax, e.bz));
    const __m128 cz = _mm_sub_ps(_mm_mul_ps(e.ax, e.by), _mm_mul_ps(e.ay, e.bx));
    const __m128 c2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(cx, cx), _mm_mul_ps(cy, cy)), _mm_mul_ps(cz, cz));
    const __m128 limit = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(1e-8f), e.a2), e.b2);
    const __m128 counts = _mm_and_ps(_mm_cmpge_ps(c2, limit), _mm_cmpgt_ps(c2, _mm_setzero_ps()));
    const __m128 sine = _mm_sqrt_ps(c2);
    const __m128 ab = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e.ax, e.bx), _mm_mul_ps(e.ay, e.by)), _mm_mul_ps(e.az, e.bz));
    const __m128 nc = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(normal.x), cx), _mm_mul_ps(_mm_set1_ps(normal.y), cy)),
                                 _mm_mul_ps(_mm_set1_ps(normal.z), cz));
    alignas(16) float cosine[4], angle[4];
    _mm_store_ps(cosine, _mm_div_ps(nc, sine));
    _mm_store_ps(angle, atan2NonNegative4(sine, ab));
    const int mask = _mm_movemask_ps(counts);
    for (int k = 0; k < 4; ++k) out[k] = {cosine[k], angle[k], (mask >> k & 1) != 0};
}

__m128 squaredLengths(__m128 x, __m128 y, __m128 z) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z));
}

// Triangles and quads, the usual emitters, in registers: the corner offsets in lanes 0 .. n-1,
// each edge's end the next lane round (lane 3 of a triangle is dropped).
float smallPolygonFormFactor(Vec3 point, Vec3 normal, std::span<const Vec3> w) {
    const size_t n = w.size();
    const Vec3& last = w[n - 1];
    EdgeLanes e;
    e.ax = _mm_sub_ps(_mm_setr_ps(w[0].x, w[1].x, w[2].x, last.x), _mm_set1_ps(point.x));
    e.ay = _mm_sub_ps(_mm_setr_ps(w[0].y, w[1].y, w[2].y, last.y), _mm_set1_ps(point.y));
    e.az = _mm_sub_ps(_mm_setr_ps(w[0].z, w[1].z, w[2].z, last.z), _mm_set1_ps(point.z));
    e.a2 = squaredLengths(e.ax, e.ay, e.az);
    auto next = [n](__m128 v) {
        return n == 4 ? _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 3, 2, 1)) : _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 0, 2, 1));
    };
    e.bx = next(e.ax), e.by = next(e.ay), e.bz = next(e.az), e.b2 = next(e.a2);
    EdgeTerm terms[4];
    edgeTerms4(normal, e, terms);
    double total = 0;
    for (size_t k = 0; k < n; ++k)
        if (!addEdge(total, terms[k])) return 0;
    return static_cast<float>(total / (2.0 * kPiD));
}

// Any other polygon: the corner offsets laid out in lanes, the first repeated after the last so
// that edge i reads slots i and i + 1, padded to whole groups of four (the padding is dropped).
float largePolygonFormFactor(Vec3 point, Vec3 normal, std::span<const Vec3> w) {
    const size_t n = w.size();
    constexpr size_t kSlots = kMaxVectorCorners + 8;
    alignas(16) float ox[kSlots], oy[kSlots], oz[kSlots], o2[kSlots];
    const size_t groups = (n + 3) / 4;
    for (size_t k = 0; k < groups * 4 + 1; ++k) {
        const Vec3 o = k <= n ? w[k % n] - point : Vec3{};
        ox[k] = o.x, oy[k] = o.y, oz[k] = o.z;
        o2[k] = dot(o, o);
    }
    double total = 0;
    EdgeTerm terms[4];
    for (size_t g = 0; g < groups; ++g) {
        const size_t i = g * 4;
        const EdgeLanes e{_mm_loadu_ps(ox + i),     _mm_loadu_ps(oy + i),     _mm_loadu_ps(oz + i),
                          _mm_loadu_ps(o2 + i),     _mm_loadu_ps(ox + i + 1), _mm_loadu_ps(oy + i + 1),
                          _mm_loadu_ps(oz + i + 1), _mm_loadu_ps(o2 + i + 1)};
        edgeTerms4(normal, e, terms);
        for (size_t k = 0; k < 4 && i + k < n; ++k)
            if (!addEdge(total, terms[k])) return 0;
    }
    return static_cast<float>(total / (2.0 * kPiD));
}
#endif

}  // namespace

float pointToPolygonFormFactorScalar(Vec3 point, Vec3 normal, std::span<const Vec3> winding) {
    const size_t n = winding.size();
    if (n < 3) return 0;
    // Each edge adds its angle seen from the point times the cosine between the normal and the
    // plane through the point and the edge. Both come from the cross and dot products of the two
    // corner offsets, whatever their lengths: the offsets need no normalising.
    double total = 0;
    Vec3 a = winding[0] - point;
    float a2 = dot(a, a);
    for (size_t i = 1; i <= n; ++i) {
        const Vec3 b = winding[i % n] - point;
        const float b2 = dot(b, b);
        if (!addEdge(total, edgeTerm(normal, a, a2, b, b2))) return 0;
        a = b;
        a2 = b2;
    }
    return static_cast<float>(total / (2.0 * kPiD));
}

float pointToPolygonFormFactor(Vec3 point, Vec3 normal, std::span<const Vec3> winding) {
#if defined(__SSE2__)
    const size_t n = winding.size();
    if (n == 3 || n == 4) return smallPolygonFormFactor(point, normal, winding);
    if (n > 4 && n <= kMaxVectorCorners) return largePolygonFormFactor(point, normal, winding);
#endif
    return pointToPolygonFormFactorScalar(point, normal, winding);
}

EmitterBounds emitterBounds(const std::vector<Vec3>& winding) {
    EmitterBounds b;
    if (winding.size() < 3) return b;
    for (const Vec3& v : winding) {
        b.center += v;
        b.box.add(v);
    }
    b.center = b.center / static_cast<float>(winding.size());
    Vec3 newell;
    b.radius = 0;
    for (size_t i = 0; i < winding.size(); ++i) {
        b.radius = std::max(b.radius, length(winding[i] - b.center));
        newell += cross(winding[i], winding[(i + 1) % winding.size()]);
        if (i >= 1 && i + 1 < winding.size())
            b.area += 0.5f * length(cross(winding[i] - winding[0], winding[i + 1] - winding[0]));
    }
    const float newellLength = length(newell);
    if (newellLength > 0) {
        b.planeNormal = newell / newellLength;
        for (const Vec3& v : winding) b.flatness = std::max(b.flatness, std::fabs(dot(v - b.center, b.planeNormal)));
        b.flat = b.flatness <= 0.01f;
    }
    return b;
}

}  // namespace q3::light
