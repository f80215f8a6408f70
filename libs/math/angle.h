// Angles from sines and cosines without libm's double-precision path: the area-light form factor
// takes one per emitter edge per sample, which made acos a fifth of a light run.
#pragma once

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace q3 {

// atan2(y, x) for y >= 0, in [0, pi], within a few float ulps. The reduction around pi/6 keeps
// the argument of the odd series within tan(pi/12), where seven terms leave an error below 3e-10.
inline float atan2NonNegative(float y, float x) {
    constexpr float kPi = 3.14159265358979f;
    constexpr float kSqrt3 = 1.73205080756888f;
    constexpr float kTanPiOver12 = 0.267949192431123f;
    const float ax = std::fabs(x);
    const bool steep = y > ax;
    const float r = steep ? ax / y : (ax > 0 ? y / ax : 0.0f);
    float base = 0, t = r;
    if (r > kTanPiOver12) {
        t = (r * kSqrt3 - 1) / (r + kSqrt3);
        base = kPi / 6;
    }
    const float t2 = t * t;
    const float series =
        t * (1 + t2 * (-1 / 3.0f + t2 * (1 / 5.0f + t2 * (-1 / 7.0f + t2 * (1 / 9.0f + t2 * (-1 / 11.0f + t2 / 13.0f))))));
    float angle = base + series;
    if (steep) angle = kPi / 2 - angle;
    if (x < 0) angle = kPi - angle;
    return angle;
}

#if defined(__SSE2__)
// atan2NonNegative on four lanes: the same float operations in the same order, so each lane gives
// the bits the one-lane form gives. Both branches are computed and selected per lane (the one not
// taken may divide by zero; its lanes are discarded).
inline __m128 atan2NonNegative4(__m128 y, __m128 x) {
    constexpr float kPi = 3.14159265358979f;
    constexpr float kSqrt3 = 1.73205080756888f;
    constexpr float kTanPiOver12 = 0.267949192431123f;
    auto select = [](__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); };
    const __m128 zero = _mm_setzero_ps();
    const __m128 ax = _mm_andnot_ps(_mm_set1_ps(-0.0f), x);
    const __m128 steep = _mm_cmpgt_ps(y, ax);
    const __m128 flat = select(_mm_cmpgt_ps(ax, zero), _mm_div_ps(y, ax), zero);
    const __m128 r = select(steep, _mm_div_ps(ax, y), flat);
    const __m128 sqrt3 = _mm_set1_ps(kSqrt3);
    const __m128 reduced = _mm_cmpgt_ps(r, _mm_set1_ps(kTanPiOver12));
    const __m128 shifted = _mm_div_ps(_mm_sub_ps(_mm_mul_ps(r, sqrt3), _mm_set1_ps(1.0f)), _mm_add_ps(r, sqrt3));
    const __m128 t = select(reduced, shifted, r);
    const __m128 base = select(reduced, _mm_set1_ps(kPi / 6), zero);
    const __m128 t2 = _mm_mul_ps(t, t);
    __m128 s = _mm_div_ps(t2, _mm_set1_ps(13.0f));
    s = _mm_mul_ps(t2, _mm_add_ps(_mm_set1_ps(-1 / 11.0f), s));
    s = _mm_mul_ps(t2, _mm_add_ps(_mm_set1_ps(1 / 9.0f), s));
    s = _mm_mul_ps(t2, _mm_add_ps(_mm_set1_ps(-1 / 7.0f), s));
    s = _mm_mul_ps(t2, _mm_add_ps(_mm_set1_ps(1 / 5.0f), s));
    s = _mm_mul_ps(t2, _mm_add_ps(_mm_set1_ps(-1 / 3.0f), s));
    const __m128 series = _mm_mul_ps(t, _mm_add_ps(_mm_set1_ps(1.0f), s));
    __m128 angle = _mm_add_ps(base, series);
    angle = select(steep, _mm_sub_ps(_mm_set1_ps(kPi / 2), angle), angle);
    angle = select(_mm_cmplt_ps(x, zero), _mm_sub_ps(_mm_set1_ps(kPi), angle), angle);
    return angle;
}
#endif

}  // namespace q3
