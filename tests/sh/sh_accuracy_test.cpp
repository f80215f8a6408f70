// Accuracy of SH irradiance against brute force for scenes of unoccluded lights (sh-grid.md).
// Max error <= 0.0938 * sum|C_j| per channel always. Mean error: 0.0230 (exactly 0.0230053) is
// the mean for one light evaluated with the clamp max(0, .) and nothing else lighting the point;
// once ambient or other lights lift the ringing lobe (down to -0.0396 C) above zero the clamp no
// longer removes it, and the guaranteed bound is the unclamped single-light mean 0.0306737 * sum|C_j|
// (triangle inequality). Both facts are asserted. Smooth environments stay within 3% mean relative
// error; opposite colours are told apart.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sh.h"
#include "sh_test_support.h"

namespace q3::sh {
namespace {

struct Light {
    Vec3d dir;
    Rgb color;
};

struct Scene {
    std::vector<Light> lights;
    Rgb ambient;
};

double channel(const Rgb& c, int ch) { return ch == 0 ? c.r : ch == 1 ? c.g : c.b; }

Rgb bruteForce(const Scene& scene, Vec3d n) {
    Rgb e = scene.ambient;
    for (const Light& light : scene.lights) {
        const double c = std::max(0.0, test::dot(n, light.dir));
        e.r += light.color.r * c;
        e.g += light.color.g * c;
        e.b += light.color.b * c;
    }
    return e;
}

SH9Color project(const Scene& scene) {
    SH9Color sh = projectAmbient(scene.ambient);
    for (const Light& light : scene.lights) addDirectionalIrradiance(sh, light.dir, light.color);
    return sh;
}

Scene randomScene(std::mt19937& rng, int lightCount, bool withAmbient = true) {
    std::uniform_real_distribution<double> colour(0.0, 2.0), ambient(0.0, 0.5);
    Scene scene;
    for (int j = 0; j < lightCount; ++j) scene.lights.push_back({test::randomDirection(rng), {colour(rng), colour(rng), colour(rng)}});
    if (withAmbient) scene.ambient = {ambient(rng), ambient(rng), ambient(rng)};
    return scene;
}

TEST(ShAccuracy, RandomScenesStayWithinTheTruncationBounds) {
    constexpr double kMaxBound = 0.0938, kMeanBound = 0.0306737 + 1e-6, kFloatTolerance = 1e-6;
    std::mt19937 rng(20260101);
    // Means use a dense Fibonacci lattice (a near-exact sphere average, free of sampling noise);
    // maxima use random normals.
    const std::vector<Vec3d> lattice = test::fibonacciSphere(40000);
    for (int sceneIndex = 0; sceneIndex < 30; ++sceneIndex) {
        const Scene scene = randomScene(rng, 1 + sceneIndex % 8);
        const SH9Color sh = project(scene);
        double sumAbs[3] = {0, 0, 0};
        for (const Light& light : scene.lights)
            for (int ch = 0; ch < 3; ++ch) sumAbs[ch] += std::fabs(channel(light.color, ch));

        double maxErr[3] = {0, 0, 0}, maxErrUnclamped[3] = {0, 0, 0};
        for (int k = 0; k < 5000; ++k) {
            const Vec3d n = test::randomDirection(rng);
            const Rgb exact = bruteForce(scene, n), approx = evalIrradianceClamped(sh, n), raw = evalIrradiance(sh, n);
            for (int ch = 0; ch < 3; ++ch) {
                maxErr[ch] = std::max(maxErr[ch], std::fabs(channel(exact, ch) - channel(approx, ch)));
                maxErrUnclamped[ch] = std::max(maxErrUnclamped[ch], std::fabs(channel(exact, ch) - channel(raw, ch)));
            }
        }
        double meanErr[3] = {0, 0, 0};
        for (const Vec3d& n : lattice) {
            const Rgb exact = bruteForce(scene, n), approx = evalIrradianceClamped(sh, n);
            for (int ch = 0; ch < 3; ++ch) meanErr[ch] += std::fabs(channel(exact, ch) - channel(approx, ch));
        }
        for (int ch = 0; ch < 3; ++ch) {
            meanErr[ch] /= double(lattice.size());
            EXPECT_LE(maxErr[ch], kMaxBound * sumAbs[ch] + kFloatTolerance) << "scene " << sceneIndex << " channel " << ch;
            EXPECT_LE(maxErrUnclamped[ch], kMaxBound * sumAbs[ch] + kFloatTolerance) << "scene " << sceneIndex;
            EXPECT_LE(meanErr[ch], kMeanBound * sumAbs[ch] + kFloatTolerance) << "scene " << sceneIndex << " channel " << ch;
        }
    }
}

// Mean |error| per channel over a dense lattice, clamped evaluation.
Rgb meanClampedError(const Scene& scene, const std::vector<Vec3d>& lattice) {
    const SH9Color sh = project(scene);
    double sum[3] = {0, 0, 0};
    for (const Vec3d& n : lattice) {
        const Rgb exact = bruteForce(scene, n), approx = evalIrradianceClamped(sh, n);
        for (int ch = 0; ch < 3; ++ch) sum[ch] += std::fabs(channel(exact, ch) - channel(approx, ch));
    }
    return {sum[0] / lattice.size(), sum[1] / lattice.size(), sum[2] / lattice.size()};
}

TEST(ShAccuracy, SingleLightMeanErrorIsTheSpecValue) {
    // 0.0230 of the spec, exactly 0.0230053; the tolerance covers the last digit and the lattice.
    const std::vector<Vec3d> lattice = test::fibonacciSphere(40000);
    std::mt19937 rng(77);
    for (int k = 0; k < 10; ++k) {
        const Scene scene = randomScene(rng, 1, false);
        const Rgb mean = meanClampedError(scene, lattice);
        for (int ch = 0; ch < 3; ++ch) {
            const double c = channel(scene.lights[0].color, ch);
            EXPECT_LE(channel(mean, ch), (0.0230 + 1e-5) * c + 1e-7);
            EXPECT_GE(channel(mean, ch), (0.0230 - 1e-4) * c - 1e-7);
        }
    }
}

TEST(ShAccuracy, AmbientUnderTheRingingGivesTheUnclampedMean) {
    // Ambient 0.1 lifts the ringing lobe of a unit light above zero: the clamp never acts and the
    // mean error is the unclamped 0.0306737, above the spec's 0.0230.
    const Scene scene{{{{0, 0, 1}, {1, 1, 1}}}, {0.1, 0.1, 0.1}};
    const Rgb mean = meanClampedError(scene, test::fibonacciSphere(40000));
    EXPECT_NEAR(mean.r, 0.0306737, 2e-5);
    EXPECT_GT(mean.r, 0.0230 * 1.3);
}

TEST(ShAccuracy, OneLightReachesTheMaxBoundAtTheTerminator) {
    // The bound is attained (error 0.09375 at n.l = 0), so the test above is not vacuous.
    const Scene scene{{{{0, 0, 1}, {1, 1, 1}}}, {0, 0, 0}};
    const SH9Color sh = project(scene);
    const Rgb e = evalIrradiance(sh, {1, 0, 0});
    EXPECT_NEAR(e.r, 0.09375, 1e-9);
}

TEST(ShAccuracy, SmoothEnvironmentMeanRelativeErrorUnderThreePercent) {
    // 64 lights spread evenly over the sphere, colours varying smoothly with direction: a soft
    // sky-like environment.
    Scene scene;
    for (const Vec3d& d : test::fibonacciSphere(64)) {
        const double r = 0.05 * (1.2 + 0.6 * d.z + 0.3 * d.x);
        const double g = 0.05 * (1.0 + 0.4 * d.y - 0.2 * d.z);
        const double b = 0.05 * (1.5 - 0.5 * d.z + 0.2 * d.x * d.y);
        scene.lights.push_back({d, {r, g, b}});
    }
    const SH9Color sh = project(scene);
    double relErr[3] = {0, 0, 0};
    std::mt19937 rng(64);
    const int count = 20000;
    for (int k = 0; k < count; ++k) {
        const Vec3d n = test::randomDirection(rng);
        const Rgb exact = bruteForce(scene, n), approx = evalIrradiance(sh, n);
        for (int ch = 0; ch < 3; ++ch) relErr[ch] += std::fabs(channel(approx, ch) - channel(exact, ch)) / channel(exact, ch);
    }
    for (int ch = 0; ch < 3; ++ch) EXPECT_LT(relErr[ch] / count, 0.03) << "channel " << ch;
}

TEST(ShAccuracy, AmbientAddsWithoutError) {
    std::mt19937 rng(5);
    Scene scene = randomScene(rng, 3);
    Scene noAmbient = scene;
    noAmbient.ambient = {};
    const SH9Color with = project(scene), without = project(noAmbient);
    for (int k = 0; k < 500; ++k) {
        const Vec3d n = test::randomDirection(rng);
        const Rgb a = evalIrradiance(with, n), b = evalIrradiance(without, n);
        EXPECT_NEAR(a.r - b.r, scene.ambient.r, 1e-12);
        EXPECT_NEAR(a.g - b.g, scene.ambient.g, 1e-12);
        EXPECT_NEAR(a.b - b.b, scene.ambient.b, 1e-12);
    }
}

TEST(ShAccuracy, RedBelowBlueAboveAlongY) {
    const Scene scene{{{{0, -1, 0}, {1, 0, 0}}, {{0, 1, 0}, {0, 0, 1}}}, {0.05, 0.05, 0.05}};
    const SH9Color sh = project(scene);
    const Rgb towardRed = evalIrradianceClamped(sh, {0, -1, 0});
    const Rgb towardBlue = evalIrradianceClamped(sh, {0, 1, 0});
    EXPECT_GT(towardRed.r, 4 * towardRed.b);
    EXPECT_GT(towardBlue.b, 4 * towardBlue.r);
    EXPECT_NEAR(towardRed.r, 0.05 + 1.0625, 1e-9);
    EXPECT_NEAR(towardRed.b, 0.05 + 0.0625, 1e-9);
    // Sideways both lights graze equally.
    const Rgb side = evalIrradianceClamped(sh, {1, 0, 0});
    EXPECT_NEAR(side.r, side.b, 1e-12);
}

}  // namespace
}  // namespace q3::sh
