// Moving models lit by the SH grid alone and by the SH grid plus the light cache, against brute
// force: every world light with the compiler's own occlusion at the model's exact position, plus
// what the grid holds besides those lights (area lights, ambient). On oacmpdm1 and on the
// pillar_lights sample (a red and a blue light either side of a pillar, and a spotlight), along
// paths a model could take; and the step a light makes when the model passes behind the pillar.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "lightcache_compare.h"
#include "sh_tools.h"
#include "test_data.h"

namespace q3::light {
namespace {

namespace fs = std::filesystem;

using cachetest::LitMap;
using cachetest::MapInputs;

constexpr float kNearDistance = 128;  // the "within 128 units of a point or spot light"
constexpr int kNormals = 48;

std::array<float, 3> arr(Vec3 v) { return {v.x, v.y, v.z}; }

fs::path workFor(const MapInputs& in) { return test::tempDir() / ("lightcache_" + in.bsp.stem().string()); }

struct Tally {
    double shAlone = 0, withCache = 0, truth = 0;
    int positions = 0;
    void add(const LitMap::Errors& e) {
        shAlone += e.shAlone;
        withCache += e.withCache;
        truth += e.truthScale;
        ++positions;
    }
    double alone() const { return shAlone / std::max(1, positions); }
    double cached() const { return withCache / std::max(1, positions); }
};

// Positions every `step` units along each path, those in open space, sorted into near a point or
// spot light and elsewhere.
void tallyPaths(const LitMap& map, const std::vector<std::pair<Vec3, Vec3>>& paths, float step, Tally& near,
                Tally& elsewhere) {
    const std::vector<Vec3> normals = cachetest::fibonacciNormals(kNormals);
    for (const auto& [from, to] : paths) {
        const float len = length(to - from);
        const int steps = std::max(1, int(len / step));
        for (int i = 0; i <= steps; ++i) {
            const Vec3 p = from + (to - from) * (float(i) / float(steps));
            if (!map.open(p)) continue;
            const LitMap::Errors e = map.errorsAt(p, normals);
            (map.nearestLocalLight(p) <= kNearDistance ? near : elsewhere).add(e);
        }
    }
}

void expectCacheHalvesTheErrorNearLights(const Tally& near, const Tally& elsewhere, const std::string& name) {
    ASSERT_GE(near.positions, 20) << name;
    ASSERT_GE(elsewhere.positions, 20) << name;
    EXPECT_GT(near.alone(), 0) << name;
    EXPECT_LE(near.cached(), 0.5 * near.alone()) << name << ": near " << near.positions << " positions";
    EXPECT_LE(elsewhere.cached(), elsewhere.alone()) << name << ": elsewhere " << elsewhere.positions << " positions";
    std::printf("%s: within %g units of a light (%d positions) mean error %.4f alone, %.4f with the cache; "
                "elsewhere (%d) %.4f / %.4f; mean brute-force irradiance %.4f / %.4f\n",
                name.c_str(), double(kNearDistance), near.positions, near.alone(), near.cached(), elsewhere.positions,
                elsewhere.alone(), elsewhere.cached(), near.truth / std::max(1, near.positions),
                elsewhere.truth / std::max(1, elsewhere.positions));
}

MapInputs pillarRoom() {
    const fs::path samples(fs::path(Q3MAP_SOURCE_DIR) / "bsp-samples");
    return {samples / "golden/pillar_lights.bsp", samples / "samples/maps/pillar_lights.map", {}, ""};
}

TEST(LightCacheAccuracy, PillarRoomPathsHalveTheGridsErrorNearLights) {
    const LitMap map(pillarRoom(), workFor(pillarRoom()));
    ASSERT_EQ(map.error(), "");
    ASSERT_EQ(map.listedLights(), 3u);
    ASSERT_EQ(map.cache().lights().size(), 3u);
    // Walks across the room at two heights, around the pillar (224..288 on x and y), and under
    // the spotlight at (256 448 224).
    std::vector<std::pair<Vec3, Vec3>> paths;
    for (float z : {40.f, 120.f}) {
        for (float y : {40.f, 120.f, 192.f, 256.f, 320.f, 400.f, 470.f}) paths.push_back({{20, y, z}, {492, y, z}});
        for (float x : {60.f, 160.f, 256.f, 352.f, 450.f}) paths.push_back({{x, 20, z}, {x, 492, z}});
    }
    Tally near, elsewhere;
    tallyPaths(map, paths, 8, near, elsewhere);
    expectCacheHalvesTheErrorNearLights(near, elsewhere, "pillar_lights");
}

// A model walking north at x = 400 passes behind the pillar as the red light (96 256 128) sees
// it: the red light leaves the local set for the stretch the pillar hides it, and its light on
// the model's west side steps to nothing there, where the SH grid only blurs it.
TEST(LightCacheAccuracy, PassingBehindThePillarDropsTheRedLight) {
    const LitMap map(pillarRoom(), workFor(pillarRoom()));
    ASSERT_EQ(map.error(), "");
    int red = -1;
    for (size_t i = 0; i < map.cache().lights().size(); ++i) {
        const sh::WorldLight& l = map.cache().lights()[i];
        if (l.intensity[0] > 0 && l.intensity[2] == 0) red = int(i);
    }
    ASSERT_GE(red, 0);
    const Vec3 west{-1, 0, 0};
    auto redLocal = [&](float y, float* westRed) {
        const float at[3] = {400, y, 64};
        const sh::LightCacheResult r = map.cache().query(at);
        *westRed = 0;
        bool found = false;
        for (int i = 0; i < r.localCount; ++i)
            if (int(r.local[i].index) == red) {
                found = true;
                *westRed = sh::evaluateWorldLight(map.cache().lights()[size_t(red)], {400, y, 64}, arr(west))[0];
            }
        return found;
    };
    std::vector<float> hiddenAt;
    float largestStep = 0, lastRed = 0;
    for (float y = 40; y <= 472; y += 8) {
        float westRed = 0;
        const bool local = redLocal(y, &westRed);
        if (!local) hiddenAt.push_back(y);
        if (y > 40) largestStep = std::max(largestStep, std::fabs(westRed - lastRed));
        lastRed = westRed;
    }
    // The pillar's shadow from the light through x = 400: y within about 256 +- 32 * (304 / 128 + 1).
    ASSERT_FALSE(hiddenAt.empty());
    EXPECT_GE(hiddenAt.front(), 150);
    EXPECT_LE(hiddenAt.back(), 362);
    EXPECT_TRUE(std::find(hiddenAt.begin(), hiddenAt.end(), 256.f) != hiddenAt.end());
    float atSide = 0, behind = 0;
    EXPECT_TRUE(redLocal(64, &atSide));
    EXPECT_FALSE(redLocal(256, &behind));
    EXPECT_GT(atSide, 0);
    EXPECT_EQ(behind, 0);
    // One 8-unit step carries most of the light: a step, not a ramp.
    EXPECT_GT(largestStep, 0.5f * atSide);
}

// -shprobe prints what the cache picks: behind the pillar the red light is hidden, beside it both
// coloured lights are local (the spotlight's cone does not reach either point).
TEST(LightCacheAccuracy, ShProbeListsTheLightsTheCachePicks) {
    const LitMap map(pillarRoom(), workFor(pillarRoom()));
    ASSERT_EQ(map.error(), "");
    auto probe = [&](float y) {
        const float at[3] = {400, y, 64};
        return shtools::probeBsp(map.cacheBytes(), at, "pillar_lights.bsp");
    };
    const shtools::ProbeReport beside = probe(64), behind = probe(256);
    ASSERT_TRUE(beside.hasWorldLights);
    EXPECT_EQ(beside.cache.localCount, 2);
    EXPECT_EQ(beside.cache.occludedCount, 0u);
    EXPECT_EQ(behind.cache.localCount, 1);
    EXPECT_EQ(behind.cache.occludedCount, 1u);
    const std::vector<std::string> lines = shtools::formatProbeReport(behind);
    const std::string text = std::accumulate(lines.begin(), lines.end(), std::string(),
                                             [](std::string a, const std::string& b) { return a + b + "\n"; });
    EXPECT_NE(text.find("light cache: 3 world lights; cluster "), std::string::npos) << text;
    EXPECT_NE(text.find(": 1 local, 0 projected into the probe, 1 hidden"), std::string::npos) << text;
    EXPECT_NE(text.find("  local 1: light 1, point at (416 256 128), arriving"), std::string::npos) << text;
}

// The path picture: in the pillar room the light cache is brute force to the display byte, the SH
// grid alone is not (it blurs the lights' direction and the pillar's shadow).
TEST(LightCacheAccuracy, PathPictureRowsAreBruteForceGridAndCache) {
    const LitMap map(pillarRoom(), workFor(pillarRoom()));
    ASSERT_EQ(map.error(), "");
    std::vector<Vec3> positions;
    for (float y = 40; y <= 472; y += 48) positions.push_back({400, y, 64});
    constexpr int kCell = 24;
    const Image image = cachetest::renderPathPicture(map, positions, kCell, 2.0f);
    ASSERT_EQ(image.width, int(positions.size()) * kCell);
    ASSERT_EQ(image.height, 3 * kCell);
    int cacheOff = 0, gridOff = 0, lit = 0;
    for (int y = 0; y < kCell; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int ch = 0; ch < 3; ++ch) {
                const int truth = image.texel(x, y)[ch];
                lit += truth > 40;
                cacheOff = std::max(cacheOff, std::abs(image.texel(x, y + 2 * kCell)[ch] - truth));
                gridOff = std::max(gridOff, std::abs(image.texel(x, y + kCell)[ch] - truth));
            }
    EXPECT_GT(lit, 1000);
    EXPECT_LE(cacheOff, 2);
    EXPECT_GE(gridOff, 20);
}

// oacmpdm1 as shipped, relit: paths from every player start towards every point or spot light
// within 512 units, and between neighbouring starts.
TEST(LightCacheAccuracy, Oacmpdm1PathsHalveTheGridsErrorNearLights) {
    const fs::path shipped = test::realBsp("oacmpdm1");
    fs::path mapSource;
    for (const fs::path& p : test::oacmpMapSources())
        if (p.stem() == "oacmpdm1") mapSource = p;
    ASSERT_FALSE(mapSource.empty()) << "oacmpdm1.map missing from the data cache";
    const MapInputs in{shipped, mapSource, {test::openArenaBase().string()}, "baseoa"};
    const LitMap map(in, workFor(in));
    ASSERT_EQ(map.error(), "");
    ASSERT_GT(map.listedLights(), 10u);
    const bsp::Bsp b = bsp::readBsp(shipped);
    std::vector<Vec3> starts;
    for (const bsp::Entity& e : bsp::parseEntities(b.entities, "oacmpdm1.bsp"))
        if (e.value("classname") == "info_player_deathmatch") {
            Vec3 o;
            if (std::sscanf(e.value("origin").c_str(), "%f %f %f", &o.x, &o.y, &o.z) == 3) starts.push_back(o);
        }
    ASSERT_GE(starts.size(), 4u);
    std::vector<std::pair<Vec3, Vec3>> paths;
    for (const Vec3& s : starts) {
        for (const sh::WorldLight& l : map.cache().lights()) {
            if (l.type == sh::WorldLightType::Sun) continue;
            const Vec3 o{l.origin[0], l.origin[1], l.origin[2]};
            const float d = length(o - s);
            if (d > 512 || d < 48) continue;
            paths.push_back({s, s + (o - s) * ((d - 24) / d)});  // stop short of the light itself
        }
    }
    for (size_t i = 0; i + 1 < starts.size(); ++i) paths.push_back({starts[i], starts[i + 1]});
    Tally near, elsewhere;
    tallyPaths(map, paths, 16, near, elsewhere);
    expectCacheHalvesTheErrorNearLights(near, elsewhere, "oacmpdm1");
}

}  // namespace
}  // namespace q3::light
