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

}  // namespace

PolygonMoments sphericalPolygonMoments(std::span<const Vec3d> corners) {
    PolygonMoments m;
    // Called per light and probe: the unit corners live on the stack for the usual emitters.
    constexpr size_t kOnStack = 32;
    Vec3d onStack[kOnStack];
    thread_local std::vector<Vec3d> onHeap;
    Vec3d* v = onStack;
    if (corners.size() > kOnStack) {
        onHeap.resize(corners.size());
        v = onHeap.data();
    }
    size_t n = 0;
    for (const Vec3d& c : corners) {
        const Vec3d unit = normalized(c);
        if (dot(unit, unit) > 0) v[n++] = unit;
    }
    if (n < 3) return m;
    // Solid angle of the fan from the first corner: each triangle (a, b, c) spans twice the
    // argument of 1 + a.b + b.c + c.a + i a.(b x c) (Van Oosterom and Strackee 1983), signed by
    // the winding. The arguments add up as the complex numbers multiply, so one atan2 gives the
    // sum; it stays within (-pi, pi) because a polygon seen from off its plane covers under 2 pi.
    double re = 1, im = 0;
    for (size_t k = 1; k + 1 < n; ++k) {
        const Vec3d &a = v[0], &b = v[k], &c = v[k + 1];
        const double numerator = dot(a, cross(b, c));
        const double denominator = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
        const double r = re * denominator - im * numerator;
        im = re * numerator + im * denominator;
        re = r;
        const double size = std::max(std::abs(re), std::abs(im));
        if (size > 1e100 || (size < 1e-100 && size > 0)) {  // each factor is at most 4: rarely taken
            re /= size;
            im /= size;
        }
    }
    const double omega = 2.0 * std::atan2(im, re);
    // Windings that run one way have positive signed area; v_k x v_k+1 then points into the cone.
    const double inward = omega >= 0 ? 1.0 : -1.0;
    m.solidAngle = std::abs(omega);
    if (!(m.solidAngle > 0)) return PolygonMoments{};
    Vec3d first;
    double xx = 0, yy = 0, zz = 0, xy = 0, yz = 0, xz = 0;  // the symmetric edge terms
    for (size_t k = 0; k < n; ++k) {
        const Vec3d a = v[k], b = v[k + 1 == n ? 0 : k + 1];
        const Vec3d axis = cross(a, b);
        const double sine = std::sqrt(dot(axis, axis));
        if (!(sine > 0)) continue;
        const double cosine = std::clamp(dot(a, b), -1.0, 1.0);
        const double angle = std::atan2(sine, cosine);
        const double inverseSine = 1.0 / sine;
        const Vec3d outward = axis * (-inward * inverseSine);
        first = first - outward * (0.5 * angle);
        // u: unit, in the edge's plane, orthogonal to a towards b (|b - a cos| = sin for unit a, b).
        const Vec3d u = (b - a * cosine) * inverseSine;
        // 1 - cos without the cancellation of small angles.
        const double versine = cosine > 0 ? sine * sine / (1.0 + cosine) : 1.0 - cosine;
        const Vec3d arc = a * sine + u * versine;
        xx += outward.x * arc.x;
        yy += outward.y * arc.y;
        zz += outward.z * arc.z;
        xy += 0.5 * (outward.x * arc.y + outward.y * arc.x);
        yz += 0.5 * (outward.y * arc.z + outward.z * arc.y);
        xz += 0.5 * (outward.x * arc.z + outward.z * arc.x);
    }
    m.first = first;
    const double edgeTerms[3][3] = {{xx, xy, xz}, {xy, yy, yz}, {xz, yz, zz}};
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
