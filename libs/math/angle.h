// Angles from sines and cosines without libm's double-precision path: the area-light form factor
// takes one per emitter edge per sample, which made acos a fifth of a light run.
#pragma once

#include <cmath>

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

}  // namespace q3
