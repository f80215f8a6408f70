// The sun-ray walk of sky_ray_solid.h: its compact walk against the plain walk over the BSP lumps,
// and its hull shortcut against walks of segments inside the hull, on a real map with leaves that
// hold casters or were subdivided chosen by a fixed pattern.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bspfile.h"
#include "sky_ray_solid.h"
#include "test_data.h"

namespace q3::light {
namespace {

TraceLeafContents patternContents(const bsp::Bsp& b) {
    TraceLeafContents contents;
    contents.holdsPieces.resize(b.leafs.size());
    contents.subdivided.resize(b.leafs.size());
    for (size_t l = 0; l < b.leafs.size(); ++l) {
        contents.holdsPieces[l] = l % 5 != 0 ? 1 : 0;  // some branches hold no caster at all
        contents.subdivided[l] = l % 11 == 0 ? 1 : 0;
    }
    return contents;
}

TEST(SkyRaySolid, CompactWalkMatchesThePlainOne) {
    for (const std::string name : {"oacmpdm8", "oacmpdm1"}) {
        const bsp::Bsp b = bsp::readBsp(test::realBsp(name));
        const SkyRaySolid solid(b, patternContents(b));
        const bsp::Model& world = b.models[0];
        std::mt19937 rng(11);
        auto coord = [&](int axis) {
            const float t = std::uniform_real_distribution<float>(-0.1f, 1.1f)(rng);
            const float v = world.mins[axis] + t * (world.maxs[axis] - world.mins[axis]);
            return rng() % 3 == 0 ? std::round(v) : v;  // whole values sit on axial planes
        };
        int stops = 0;
        for (int i = 0; i < 20000; ++i) {
            const Vec3 p{coord(0), coord(1), coord(2)}, q{coord(0), coord(1), coord(2)};
            const bool compact = solid.stops(p, q);
            ASSERT_EQ(compact, solid.stopsByPlainWalk(p, q)) << name << " " << i;
            stops += compact ? 1 : 0;
        }
        EXPECT_GT(stops, 1000) << name;
        EXPECT_GT(20000 - stops, 100) << name;  // open segments too
    }
}

TEST(SkyRaySolid, ClearHullsHoldNoSegmentThatStops) {
    const bsp::Bsp b = bsp::readBsp(test::realBsp("oacmpdm8"));
    const SkyRaySolid solid(b, patternContents(b));
    const bsp::Model& world = b.models[0];
    std::mt19937 rng(5);
    auto inWorld = [&] {
        Vec3 p;
        for (int a = 0; a < 3; ++a)
            p[a] = world.mins[a] + std::uniform_real_distribution<float>(0, 1)(rng) * (world.maxs[a] - world.mins[a]);
        return p;
    };
    int clear = 0;
    for (int i = 0; i < 3000; ++i) {
        // Eight probes in a small box and their ends far along one direction, as a block's sun rays.
        const Vec3 centre = inWorld();
        const Vec3 dir = normalize(Vec3{std::uniform_real_distribution<float>(-1, 1)(rng),
                                        std::uniform_real_distribution<float>(-1, 1)(rng), 1.0f});
        const float reach = std::uniform_real_distribution<float>(16, 512)(rng);
        std::vector<Vec3> ends;
        for (int k = 0; k < 8; ++k) {
            const Vec3 p = centre + Vec3{float(k & 1) * 24, float((k >> 1) & 1) * 24, float((k >> 2) & 1) * 48};
            ends.push_back(p);
            ends.push_back(p + dir * reach);
        }
        if (!solid.hullClear(ends)) continue;
        ++clear;
        // Segments between any two points of the hull, here between mixes of the ends.
        for (int j = 0; j < 40; ++j) {
            auto mix = [&] {
                const size_t a = rng() % ends.size(), c = rng() % ends.size();
                const float t = std::uniform_real_distribution<float>(0, 1)(rng);
                return ends[a] + (ends[c] - ends[a]) * t;
            };
            const Vec3 p = mix(), q = mix();
            ASSERT_FALSE(solid.stops(p, q)) << i << " " << j;
        }
    }
    EXPECT_GT(clear, 100);
}

}  // namespace
}  // namespace q3::light
