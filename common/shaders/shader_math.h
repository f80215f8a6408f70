// Pure conversions q3map2 applies to shader directive values.
#pragma once

#include <cmath>

#include "vec3.h"

namespace q3 {

// q3map2's ColorNormalize: scales so the largest component is 1. A colour without a positive
// component becomes white (q3map2 does this for all-zero colours).
inline Vec3 normalizeShaderColor(Vec3 c) {
    float m = maxComponent(c);
    if (!(m > 0)) return {1, 1, 1};
    return c / m;
}

// Direction towards a sun given as yaw (0 = +x/east, 90 = +y/north) and elevation (0 = horizon,
// 90 = straight up), both in degrees: (cos yaw cos elev, sin yaw cos elev, sin elev).
inline Vec3 sunDirectionFromAngles(double yawDegrees, double elevationDegrees) {
    const double yaw = yawDegrees * (kPiD / 180.0);
    const double elevation = elevationDegrees * (kPiD / 180.0);
    return {static_cast<float>(std::cos(yaw) * std::cos(elevation)),
            static_cast<float>(std::sin(yaw) * std::cos(elevation)), static_cast<float>(std::sin(elevation))};
}

}  // namespace q3
