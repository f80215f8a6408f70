// Polygon moments by the divergence theorem on the cone from the point over A (see sh_polygon.h).
// With n_k the outward normal of the cone's side through edge k (corners v_k, v_k+1, angle T_k):
//   field w (constant):         0 = w.first + sum_k (w.n_k) T_k / 2
//   field (w.x) w (div = 1):    |A| / 3 = w.second.w + sum_k (w.n_k)(w.F_k) / 3,
// where F_k = integral over the edge's arc of w(t) dt = v_k sin T_k + u_k (1 - cos T_k), u_k the
// unit vector of the edge's plane orthogonal to v_k towards v_k+1.
#include "sh_polygon.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace q3::sh {
namespace {

Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3d operator*(Vec3d a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double component(Vec3d v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

// Solid angle of the spherical triangle of unit vectors (Van Oosterom and Strackee 1983), signed
// by the winding.
double signedTriangleSolidAngle(Vec3d a, Vec3d b, Vec3d c) {
    const double numerator = dot(a, cross(b, c));
    const double denominator = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
    return 2.0 * std::atan2(numerator, denominator);
}

}  // namespace

PolygonMoments sphericalPolygonMoments(std::span<const Vec3d> corners) {
    PolygonMoments m;
    thread_local std::vector<Vec3d> v;  // called per light and probe: no allocation once warm
    v.clear();
    for (const Vec3d& c : corners) {
        const Vec3d unit = normalized(c);
        if (dot(unit, unit) > 0) v.push_back(unit);
    }
    const size_t n = v.size();
    if (n < 3) return m;
    double omega = 0;
    for (size_t k = 1; k + 1 < n; ++k) omega += signedTriangleSolidAngle(v[0], v[k], v[k + 1]);
    // Windings that run one way have positive signed area; v_k x v_k+1 then points into the cone.
    const double inward = omega >= 0 ? 1.0 : -1.0;
    m.solidAngle = std::abs(omega);
    if (!(m.solidAngle > 0)) return PolygonMoments{};
    Vec3d first;
    double edgeTerms[3][3] = {};
    for (size_t k = 0; k < n; ++k) {
        const Vec3d a = v[k], b = v[(k + 1) % n];
        const Vec3d axis = cross(a, b);
        const double sine = std::sqrt(dot(axis, axis));
        if (!(sine > 0)) continue;
        const double cosine = std::clamp(dot(a, b), -1.0, 1.0);
        const double angle = std::atan2(sine, cosine);
        const Vec3d outward = axis * (-inward / sine);
        first = first - outward * (0.5 * angle);
        const Vec3d u = normalized(b - a * cosine);
        const Vec3d arc = a * sine + u * (1.0 - cosine);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                edgeTerms[i][j] += 0.5 * (component(outward, i) * component(arc, j) +
                                          component(outward, j) * component(arc, i));
    }
    m.first = first;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m.second[i][j] = ((i == j ? m.solidAngle : 0.0) - edgeTerms[i][j]) / 3.0;
    return m;
}

void addUniformPolygonIrradiance(SH9Color& acc, const PolygonMoments& m, Rgb radiance) {
    const double(&s)[3][3] = m.second;
    for (int i = 0; i < kCoeffCount; ++i) {
        double integral = 0;
        switch (kBasis[i].poly) {
            case BasisPolynomial::One: integral = m.solidAngle; break;
            case BasisPolynomial::X: integral = m.first.x; break;
            case BasisPolynomial::Y: integral = m.first.y; break;
            case BasisPolynomial::Z: integral = m.first.z; break;
            case BasisPolynomial::XY: integral = s[0][1]; break;
            case BasisPolynomial::YZ: integral = s[1][2]; break;
            case BasisPolynomial::XZ: integral = s[0][2]; break;
            case BasisPolynomial::ThreeZZMinusOne: integral = 3.0 * s[2][2] - m.solidAngle; break;
            case BasisPolynomial::XXMinusYY: integral = s[0][0] - s[1][1]; break;
        }
        const double k = kClampedCosine[kBasis[i].band] * kBasis[i].constant * integral;
        acc.c[i][0] += k * radiance.r;
        acc.c[i][1] += k * radiance.g;
        acc.c[i][2] += k * radiance.b;
    }
}

}  // namespace q3::sh
