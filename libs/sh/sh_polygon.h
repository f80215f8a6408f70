// Exact L2 irradiance of a uniformly bright convex polygon (an area light), from the polygon's
// angular moments: solid angle, first moment and second moment over the spherical polygon it
// covers. Integrating the basis polynomials over the polygon replaces cutting it into pieces.
#pragma once

#include <span>

#include "sh.h"

namespace q3::sh {

// Integrals over the spherical polygon A that a convex planar polygon covers seen from a point off
// its plane: solidAngle = |A|, first = integral of w dw, second[i][j] = integral of w_i w_j dw.
struct PolygonMoments {
    double solidAngle = 0;
    Vec3d first;
    double second[3][3] = {};
};

// `corners`: the polygon's corners relative to the point (any length, either winding). Fewer than
// three usable corners, or a polygon seen edge-on, gives all zeros.
PolygonMoments sphericalPolygonMoments(std::span<const Vec3d> corners);

// Adds the irradiance of radiance L arriving uniformly from A: A_l * L * integral of Y_i over A.
void addUniformPolygonIrradiance(SH9Color& acc, const PolygonMoments& moments, Rgb radiance);

}  // namespace q3::sh
