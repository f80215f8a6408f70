// Cubemap projection against closed forms: texel solid angles against a numerical integral, and the
// SH of a constant environment, of a single bright texel and of a linear gradient along each axis,
// for several face sizes. Tolerances are stated per test; the quadrature error of a smooth
// environment falls as 1/N^2, which the gradient test checks as well.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "sh_cubemap.h"

namespace q3::sh {
namespace {

constexpr int kSizes[] = {1, 2, 4, 8, 16, 64};

Cubemap filledCubemap(int size, const std::function<Rgb(Vec3d)>& radiance) {
    Cubemap faces;
    for (int f = 0; f < kCubeFaceCount; ++f) {
        faces[size_t(f)].size = size;
        for (int row = 0; row < size; ++row)
            for (int col = 0; col < size; ++col)
                faces[size_t(f)].texels.push_back(radiance(cubeTexelDirection(CubeFace(f), col, row, size)));
    }
    return faces;
}

// Solid angle of a texel by brute force: the area element du dv / (1 + u^2 + v^2)^(3/2) summed on a
// fine grid inside the texel (independent of the closed form under test).
double numericalSolidAngle(int col, int row, int size, int steps) {
    const double texel = 2.0 / size, h = texel / steps;
    double sum = 0;
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const double u = -1 + texel * col + h * (i + 0.5), v = -1 + texel * row + h * (j + 0.5);
            sum += h * h / std::pow(1 + u * u + v * v, 1.5);
        }
    return sum;
}

// Integral of Y_i over one texel of `face` by brute force (fine grid of sub-texels).
Basis numericalTexelIntegral(CubeFace face, int col, int row, int size, int steps) {
    const CubeFaceAxes a = cubeFaceAxes(face);
    const double texel = 2.0 / size, h = texel / steps;
    Basis out{};
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const double u = -1 + texel * col + h * (i + 0.5), v = -1 + texel * row + h * (j + 0.5);
            const double w = h * h / std::pow(1 + u * u + v * v, 1.5);
            const Vec3d d = normalized({a.outward.x + u * a.right.x + v * a.down.x,
                                        a.outward.y + u * a.right.y + v * a.down.y,
                                        a.outward.z + u * a.right.z + v * a.down.z});
            const Basis y = evalBasis(d);
            for (int k = 0; k < kCoeffCount; ++k) out[size_t(k)] += w * y[size_t(k)];
        }
    return out;
}

TEST(CubemapProjection, FaceAxesAreRightHandedAsDocumented) {
    for (int f = 0; f < kCubeFaceCount; ++f) {
        const CubeFaceAxes a = cubeFaceAxes(CubeFace(f));
        const Vec3d c{a.right.y * a.down.z - a.right.z * a.down.y, a.right.z * a.down.x - a.right.x * a.down.z,
                      a.right.x * a.down.y - a.right.y * a.down.x};
        EXPECT_EQ(c.x, a.outward.x) << cubeFaceName(CubeFace(f));
        EXPECT_EQ(c.y, a.outward.y);
        EXPECT_EQ(c.z, a.outward.z);
    }
    // Top-left texel of +X: above the horizon (row 0 is the top) and towards +Y (column 0 is left).
    const Vec3d d = cubeTexelDirection(CubeFace::PosX, 0, 0, 4);
    EXPECT_GT(d.x, 0);
    EXPECT_GT(d.y, 0);
    EXPECT_GT(d.z, 0);
}

TEST(CubemapProjection, TexelSolidAnglesAreExact) {
    for (int size : kSizes) {
        double total = 0;
        for (int row = 0; row < size; ++row)
            for (int col = 0; col < size; ++col) total += cubeTexelSolidAngle(col, row, size);
        EXPECT_NEAR(6 * total, 4 * kPi, 1e-12) << "size " << size;
        // Corner and centre texels against a 400 x 400 numerical integral (relative 1e-5).
        for (auto [col, row] : {std::pair{0, 0}, std::pair{size / 2, size / 2}, std::pair{size - 1, 0}}) {
            const double exact = cubeTexelSolidAngle(col, row, size);
            EXPECT_NEAR(exact, numericalSolidAngle(col, row, size, 400), 1e-5 * exact) << size << " " << col;
        }
    }
    // The whole face is a sixth of the sphere; the centre texel of a large face is ~ its flat area.
    EXPECT_NEAR(cubeAreaElement(1, 1) * 4, 4 * kPi / 6, 1e-12);
    EXPECT_NEAR(cubeTexelSolidAngle(32, 32, 65), (2.0 / 65) * (2.0 / 65), 1e-6);
}

TEST(CubemapProjection, ConstantEnvironment) {
    // Closed form: L0 = c * 2 sqrt(pi), every other coefficient 0; irradiance pi * c for every normal.
    // Tolerance 1e-10 (rounding only: the exact solid angles sum to 4 pi and the face symmetry
    // cancels the other bands).
    const Rgb c{0.7, 1.3, 2.0};
    for (int size : kSizes) {
        SH9Color radiance;
        ASSERT_EQ(projectCubemap(filledCubemap(size, [&](Vec3d) { return c; }), radiance), "");
        EXPECT_NEAR(radiance.c[0][0], c.r * kUniformToCoeff0, 1e-10);
        EXPECT_NEAR(radiance.c[0][1], c.g * kUniformToCoeff0, 1e-10);
        EXPECT_NEAR(radiance.c[0][2], c.b * kUniformToCoeff0, 1e-10);
        for (int i = 1; i < kCoeffCount; ++i)
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(radiance.c[i][ch], 0, 1e-10) << "size " << size << " c" << i;
        const SH9Color irradiance = convolveRadianceToIrradiance(radiance);
        for (Vec3d n : {Vec3d{0, 0, 1}, Vec3d{1, 0, 0}, normalized({1, -2, 3})})
            EXPECT_NEAR(evalIrradiance(irradiance, n).b, kPi * c.b, 1e-9);
    }
}

TEST(CubemapProjection, SingleBrightTexel) {
    // Closed form: V * integral of Y_i over the texel. The projection evaluates Y_i at the texel
    // centre, so it differs by the midpoint-rule error, bounded here by 0.3 * V * omega * (2/N)^2
    // (Y_i varies by at most ~3 per radian^2 and the texel spans about 2/N radians); the total
    // (coefficient 0) is exact to 1e-12.
    const double V = 50;
    for (int size : {1, 2, 4, 8, 16, 64})
        for (int f = 0; f < kCubeFaceCount; ++f) {
            const int col = (size * 3) / 4, row = size / 4;
            Cubemap faces = filledCubemap(size, [](Vec3d) { return Rgb{}; });
            faces[size_t(f)].texels[size_t(row) * size_t(size) + size_t(col)] = {V, 0, V / 2};
            SH9Color radiance;
            ASSERT_EQ(projectCubemap(faces, radiance), "");
            const double omega = cubeTexelSolidAngle(col, row, size);
            const Basis truth = numericalTexelIntegral(CubeFace(f), col, row, size, 200);
            const double tolerance = 0.3 * V * omega * (2.0 / size) * (2.0 / size);
            EXPECT_NEAR(radiance.c[0][0], V * omega * evalBasis({0, 0, 1})[0], 1e-12 * V);
            for (int i = 0; i < kCoeffCount; ++i) {
                EXPECT_NEAR(radiance.c[i][0], V * truth[size_t(i)], tolerance)
                    << "size " << size << " face " << cubeFaceName(CubeFace(f)) << " c" << i;
                EXPECT_NEAR(radiance.c[i][2], 0.5 * radiance.c[i][0], 1e-12 * V);
                EXPECT_EQ(radiance.c[i][1], 0);
            }
        }
}

TEST(CubemapProjection, LinearGradientAlongEachAxis) {
    // L(w) = a + b (w . d): L0 = a * 2 sqrt(pi), band 1 = b * sqrt(4 pi / 3) * d (order y, z, x),
    // band 2 = 0; irradiance E(n) = pi a + (2 pi / 3) b (n . d). The texel-centre quadrature is exact
    // for it at every size: the cube's symmetry makes sum(omega * w w^T) = (4 pi / 3) I exactly, so
    // the tolerance is rounding only (1e-11).
    const double a = 2, b = 1.5;
    const double band1 = std::sqrt(4 * kPi / 3);
    for (Vec3d d : {Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}, Vec3d{0, 0, -1}, normalized({1, -2, 0.5})}) {
        for (int size : kSizes) {
            auto gradient = [&](Vec3d w) {
                const double v = a + b * (w.x * d.x + w.y * d.y + w.z * d.z);
                return Rgb{v, 0.5 * v, 0};
            };
            SH9Color radiance;
            ASSERT_EQ(projectCubemap(filledCubemap(size, gradient), radiance), "");
            EXPECT_NEAR(radiance.c[0][0], a * kUniformToCoeff0, 1e-11);
            const double expected[3] = {b * band1 * d.y, b * band1 * d.z, b * band1 * d.x};
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(radiance.c[1 + k][0], expected[k], 1e-11) << "size " << size;
            for (int i = 4; i < kCoeffCount; ++i) EXPECT_NEAR(radiance.c[i][0], 0, 1e-11) << "size " << size;
            const SH9Color irradiance = convolveRadianceToIrradiance(radiance);
            for (Vec3d n : {d, Vec3d{-d.x, -d.y, -d.z}, normalized({1, 1, 1})}) {
                const double truth = kPi * a + 2 * kPi / 3 * b * (n.x * d.x + n.y * d.y + n.z * d.z);
                EXPECT_NEAR(evalIrradiance(irradiance, n).r, truth, 1e-10);
                EXPECT_NEAR(evalIrradiance(irradiance, n).g, 0.5 * truth, 1e-10);
            }
        }
    }
}

TEST(CubemapProjection, CosineLobeConvergesAtSecondOrder) {
    // L(w) = max(0, w . d): by Funk-Hecke its coefficients are A_l * Y_i(d) (pi, 2 pi / 3, pi / 4).
    // Not polynomial, so the quadrature error is real: measured max coefficient error 0.033 at
    // N = 4 falling to 1.1e-4 at N = 64 (about 0.46 / N^2); asserted below 0.6 / N^2 and falling by
    // at least 3x per doubling of N.
    for (Vec3d d : {Vec3d{0, 0, 1}, normalized({0.3, -0.5, 0.8})}) {
        const Basis y = evalBasis(d);
        double previousError = -1;
        for (int size : {4, 8, 16, 32, 64}) {
            SH9Color radiance;
            ASSERT_EQ(projectCubemap(filledCubemap(size,
                                                   [&](Vec3d w) {
                                                       const double v = std::max(0.0, w.x * d.x + w.y * d.y + w.z * d.z);
                                                       return Rgb{v, v, v};
                                                   }),
                                     radiance),
                      "");
            double error = 0;
            for (int i = 0; i < kCoeffCount; ++i)
                error = std::max(error, std::abs(radiance.c[i][0] - kClampedCosine[kBasis[i].band] * y[size_t(i)]));
            std::printf("cosine lobe N=%d max coefficient error %.3g\n", size, error);
            EXPECT_LT(error, 0.6 / (size * size)) << "size " << size;
            if (previousError > 0) {
                EXPECT_LT(error, previousError / 3) << "size " << size;
            }
            previousError = error;
        }
    }
}

TEST(CubemapProjection, MalformedFacesAreRefused) {
    Cubemap faces = filledCubemap(4, [](Vec3d) { return Rgb{1, 1, 1}; });
    SH9Color out;
    out.c[0][0] = 42;
    Cubemap smaller = faces;
    smaller[3].size = 2;
    smaller[3].texels.resize(4);
    EXPECT_NE(projectCubemap(smaller, out).find("face -Y is 2 texels wide"), std::string::npos);
    Cubemap empty = faces;
    empty[5] = CubeFaceImage{};
    EXPECT_NE(projectCubemap(empty, out).find("face -Z is empty"), std::string::npos);
    Cubemap truncated = faces;
    truncated[1].texels.pop_back();
    EXPECT_NE(projectCubemap(truncated, out).find("face -X holds 15 texels"), std::string::npos);
    EXPECT_EQ(out.c[0][0], 42);  // untouched on error
}

}  // namespace
}  // namespace q3::sh
