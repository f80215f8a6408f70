// Polygon moments and the irradiance of uniform polygons against brute-force sums over thousands
// of tiny pieces of the planar polygon.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sh.h"
#include "sh_polygon.h"

namespace q3::sh {
namespace {

Vec3d sub(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d lerp3(Vec3d a, Vec3d b, Vec3d c, double u, double v) {
    return {a.x + (b.x - a.x) * u + (c.x - a.x) * v, a.y + (b.y - a.y) * u + (c.y - a.y) * v,
            a.z + (b.z - a.z) * u + (c.z - a.z) * v};
}
double len(Vec3d a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
Vec3d crossd(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// Every tiny triangle of a fine cut of the fan of `corners` (relative to the point), as a direction
// and the solid angle it covers (area * |cos| / r^2 at its centroid).
template <typename Visit>
void forEachPiece(const std::vector<Vec3d>& corners, int steps, Visit&& visit) {
    for (size_t t = 1; t + 1 < corners.size(); ++t) {
        const Vec3d a = corners[0], b = corners[t], c = corners[t + 1];
        const Vec3d normal = crossd(sub(b, a), sub(c, a));
        const double area = len(normal) / 2.0 / double(steps * steps);
        const Vec3d unitNormal{normal.x / len(normal), normal.y / len(normal), normal.z / len(normal)};
        auto piece = [&](double u, double v) {
            const Vec3d p = lerp3(a, b, c, u, v);
            const double r = len(p);
            const Vec3d dir{p.x / r, p.y / r, p.z / r};
            const double cosine = std::abs(dir.x * unitNormal.x + dir.y * unitNormal.y + dir.z * unitNormal.z);
            visit(dir, area * cosine / (r * r));
        };
        const double h = 1.0 / steps;
        for (int i = 0; i < steps; ++i)
            for (int j = 0; i + j < steps; ++j) {
                piece((i + 1.0 / 3) * h, (j + 1.0 / 3) * h);
                if (i + j + 1 < steps) piece((i + 2.0 / 3) * h, (j + 2.0 / 3) * h);
            }
    }
}

struct Case {
    const char* name;
    std::vector<Vec3d> corners;  // relative to the point
};

std::vector<Case> cases() {
    return {
        {"square above", {{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}}},
        {"square above, other winding", {{-1, 1, 2}, {1, 1, 2}, {1, -1, 2}, {-1, -1, 2}}},
        {"close wide square to the side", {{0.3, -3, -2}, {0.3, 3, -2}, {0.3, 3, 4}, {0.3, -3, 4}}},
        {"triangle off axis", {{2, 1, 0.5}, {3, -1, 1.5}, {1.5, 0.5, 3}}},
        {"convex hexagon below", {{1, 0, -0.7}, {0.5, 0.87, -0.7}, {-0.5, 0.87, -0.7}, {-1, 0, -0.7},
                                  {-0.5, -0.87, -0.7}, {0.5, -0.87, -0.7}}},
    };
}

TEST(ShPolygon, MomentsMatchFineSums) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        double omega = 0, first[3] = {}, second[3][3] = {};
        forEachPiece(c.corners, 300, [&](Vec3d d, double w) {
            const double comp[3] = {d.x, d.y, d.z};
            omega += w;
            for (int i = 0; i < 3; ++i) {
                first[i] += comp[i] * w;
                for (int j = 0; j < 3; ++j) second[i][j] += comp[i] * comp[j] * w;
            }
        });
        const PolygonMoments m = sphericalPolygonMoments(c.corners);
        const double tol = 2e-5 * omega;
        EXPECT_NEAR(m.solidAngle, omega, tol);
        EXPECT_NEAR(m.first.x, first[0], tol);
        EXPECT_NEAR(m.first.y, first[1], tol);
        EXPECT_NEAR(m.first.z, first[2], tol);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.second[i][j], second[i][j], tol) << i << j;
        // The trace of the second moment is the solid angle (|w| = 1).
        EXPECT_NEAR(m.second[0][0] + m.second[1][1] + m.second[2][2], m.solidAngle, 1e-12);
    }
}

TEST(ShPolygon, IrradianceMatchesManyDirectionalSamples) {
    const Rgb radiance{0.7, 0.2, 1.3};
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        SH9Color truth, exact;
        forEachPiece(c.corners, 300, [&](Vec3d d, double w) {
            addDirectionalIrradiance(truth, d, {radiance.r * w, radiance.g * w, radiance.b * w});
        });
        addUniformPolygonIrradiance(exact, sphericalPolygonMoments(c.corners), radiance);
        for (int i = 0; i < kCoeffCount; ++i)
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(exact.c[i][ch], truth.c[i][ch], 2e-5 * std::abs(truth.c[0][ch])) << i << " " << ch;
    }
}

TEST(ShPolygon, SmallFarPolygonIsOneDirection) {
    const std::vector<Vec3d> corners{{100, -0.5, -0.5}, {100, 0.5, -0.5}, {100, 0.5, 0.5}, {100, -0.5, 0.5}};
    const PolygonMoments m = sphericalPolygonMoments(corners);
    EXPECT_NEAR(m.solidAngle, 1.0 / (100.0 * 100.0), 1e-8);
    SH9Color polygon, directional;
    addUniformPolygonIrradiance(polygon, m, {1, 1, 1});
    addDirectionalIrradiance(directional, {1, 0, 0}, {m.solidAngle, m.solidAngle, m.solidAngle});
    for (int i = 0; i < kCoeffCount; ++i) EXPECT_NEAR(polygon.c[i][0], directional.c[i][0], 1e-4 * directional.c[0][0]);
}

TEST(ShPolygon, DegenerateInputGivesNothing) {
    const std::vector<Vec3d> two{{1, 0, 0}, {0, 1, 0}};
    const std::vector<Vec3d> edgeOn{{1, 0, 0}, {2, 0, 0}, {1, 1, 0}};  // the point lies in its plane, outside
    const std::vector<Vec3d> withZero{{0, 0, 0}, {1, 0, 1}, {0, 1, 1}};   // only two usable corners
    for (const auto* corners : {&two, &edgeOn, &withZero}) {
        const PolygonMoments m = sphericalPolygonMoments(*corners);
        EXPECT_EQ(m.solidAngle, 0.0);
        EXPECT_EQ(m.first.x, 0.0);
        EXPECT_EQ(m.second[2][2], 0.0);
    }
}

}  // namespace
}  // namespace q3::sh
