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

__m128 squaredLengths(__m128 x, __m128 y, __m128 z) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(y, y)), _mm_mul_ps(z, z));
}

// edgeTerm on four lanes, each with its own normal, in Vec3's order of operations: the cosine
// term, the angle, and a mask of the lanes whose edge counts.
struct EdgeTermLanes {
    __m128 cosine, angle, counts;
};
EdgeTermLanes edgeTermLanes(__m128 nx, __m128 ny, __m128 nz, const EdgeLanes& e) {
    const __m128 cx = _mm_sub_ps(_mm_mul_ps(e.ay, e.bz), _mm_mul_ps(e.az, e.by));
    const __m128 cy = _mm_sub_ps(_mm_mul_ps(e.az, e.bx), _mm_mul_ps(e.ax, e.bz));
    const __m128 cz = _mm_sub_ps(_mm_mul_ps(e.ax, e.by), _mm_mul_ps(e.ay, e.bx));
    const __m128 c2 = squaredLengths(cx, cy, cz);
    const __m128 limit = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(1e-8f), e.a2), e.b2);
    const __m128 counts = _mm_and_ps(_mm_cmpge_ps(c2, limit), _mm_cmpgt_ps(c2, _mm_setzero_ps()));
    const __m128 sine = _mm_sqrt_ps(c2);
    const __m128 ab = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e.ax, e.bx), _mm_mul_ps(e.ay, e.by)), _mm_mul_ps(e.az, e.bz));
    const __m128 nc = _mm_add_ps(_mm_add_ps(_mm_mul_ps(nx, cx), _mm_mul_ps(ny, cy)), _mm_mul_ps(nz, cz));
    return {_mm_div_ps(nc, sine), atan2NonNegative4(sine, ab), counts};
}

// Each lane's EdgeTerm (cosine, angle, counts) for one normal.
void edgeTerms4(Vec3 normal, const EdgeLanes& e, EdgeTerm out[4]) {
    const EdgeTermLanes t = edgeTermLanes(_mm_set1_ps(normal.x), _mm_set1_ps(normal.y), _mm_set1_ps(normal.z), e);
    alignas(16) float cosine[4], angle[4];
    _mm_store_ps(cosine, t.cosine);
    _mm_store_ps(angle, t.angle);
    const int mask = _mm_movemask_ps(t.counts);
    for (int k = 0; k < 4; ++k) out[k] = {cosine[k], angle[k], (mask >> k & 1) != 0};
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

void pointToPolygonFormFactor4(const FormFactorPoints& points, std::span<const Vec3> winding, float out[4]) {
    const size_t n = winding.size();
#if defined(__SSE2__)
    if (n < 3) {
        _mm_storeu_ps(out, _mm_setzero_ps());
        return;
    }
    const __m128 px = _mm_load_ps(points.x), py = _mm_load_ps(points.y), pz = _mm_load_ps(points.z);
    const __m128 nx = _mm_load_ps(points.nx), ny = _mm_load_ps(points.ny), nz = _mm_load_ps(points.nz);
    // Corner k's offset from each point, and its squared length.
    auto offset = [&](size_t k, __m128& x, __m128& y, __m128& z, __m128& s) {
        x = _mm_sub_ps(_mm_set1_ps(winding[k].x), px);
        y = _mm_sub_ps(_mm_set1_ps(winding[k].y), py);
        z = _mm_sub_ps(_mm_set1_ps(winding[k].z), pz);
        s = squaredLengths(x, y, z);
    };
    __m128 ax, ay, az, a2, fx, fy, fz, f2;
    offset(0, fx, fy, fz, f2);
    ax = fx, ay = fy, az = fz, a2 = f2;
    // Each lane's total as two pairs of doubles, and whether it has shown a broken polygon.
    __m128d totalLo = _mm_setzero_pd(), totalHi = _mm_setzero_pd();
    __m128d brokenLo = _mm_setzero_pd(), brokenHi = _mm_setzero_pd();
    const __m128d over = _mm_set1_pd(kBrokenTotal), under = _mm_set1_pd(-kBrokenTotal);
    for (size_t i = 1; i <= n; ++i) {
        __m128 bx, by, bz, b2;
        if (i == n)
            bx = fx, by = fy, bz = fz, b2 = f2;
        else
            offset(i, bx, by, bz, b2);
        const auto [cosine, angle, counts] = edgeTermLanes(nx, ny, nz, EdgeLanes{ax, ay, az, a2, bx, by, bz, b2});
        // addEdge on each lane: an edge that does not count adds a zero (a total is never -0).
        const __m128 cosineHi = _mm_movehl_ps(cosine, cosine), angleHi = _mm_movehl_ps(angle, angle);
        const __m128d lo = _mm_mul_pd(_mm_cvtps_pd(cosine), _mm_cvtps_pd(angle));
        const __m128d hi = _mm_mul_pd(_mm_cvtps_pd(cosineHi), _mm_cvtps_pd(angleHi));
        totalLo = _mm_add_pd(totalLo, _mm_and_pd(_mm_castps_pd(_mm_unpacklo_ps(counts, counts)), lo));
        totalHi = _mm_add_pd(totalHi, _mm_and_pd(_mm_castps_pd(_mm_unpackhi_ps(counts, counts)), hi));
        brokenLo = _mm_or_pd(brokenLo, _mm_or_pd(_mm_cmpgt_pd(totalLo, over), _mm_cmplt_pd(totalLo, under)));
        brokenHi = _mm_or_pd(brokenHi, _mm_or_pd(_mm_cmpgt_pd(totalHi, over), _mm_cmplt_pd(totalHi, under)));
        ax = bx, ay = by, az = bz, a2 = b2;
    }
    const __m128d turn = _mm_set1_pd(2.0 * kPiD);
    const __m128d lo = _mm_andnot_pd(brokenLo, _mm_div_pd(totalLo, turn));
    const __m128d hi = _mm_andnot_pd(brokenHi, _mm_div_pd(totalHi, turn));
    _mm_storeu_ps(out, _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi)));
#else
    for (int l = 0; l < 4; ++l)
        out[l] = pointToPolygonFormFactorScalar({points.x[l], points.y[l], points.z[l]},
                                                {points.nx[l], points.ny[l], points.nz[l]}, winding);
#endif
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
