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

#include "file_io.h"
#include "light_cache.h"
#include "light_context.h"
#include "light_contribution.h"
#include "light_stage.h"
#include "sh_tools.h"
#include "test_data.h"
#include "world_lights_export.h"

namespace q3::light {
namespace {

namespace fs = std::filesystem;

constexpr float kNearDistance = 128;  // the "within 128 units of a point or spot light"
constexpr int kNormals = 48;

struct MapInputs {
    fs::path bsp;                        // the unlit input
    fs::path mapSource;                  // its .map, where -light finds the light entities
    std::vector<std::string> basePaths;  // game data for the shaders, if any
    std::string fsGame;
};

CommonOptions commonFor(const MapInputs& in, const fs::path& bsp, const std::string& commandLine) {
    CommonOptions common;
    common.mapPath = bsp;
    common.basePaths = in.basePaths;
    common.fsGame = in.fsGame;
    common.threads = 2;
    common.commandLine = commandLine;
    return common;
}

LightOptions fastGridOptions() {
    LightOptions options;
    options.fast = true;
    options.noLightmaps = true;  // models are lit by the grid and the lights only
    options.sh = true;
    options.worldLights = true;
    return options;
}

// Lights a copy of the input in its own folder and returns the written file's bytes.
std::vector<uint8_t> lightCopy(const MapInputs& in, const fs::path& dir, const LightOptions& options,
                               const std::string& commandLine) {
    fs::create_directories(dir / "maps");
    const fs::path bsp = dir / "maps" / in.bsp.filename();
    fs::copy_file(in.bsp, bsp, fs::copy_options::overwrite_existing);
    fs::copy_file(in.mapSource, fs::path(bsp).replace_extension(".map"), fs::copy_options::overwrite_existing);
    Log log(false);
    EXPECT_EQ(runLightStage(options, commonFor(in, bsp, commandLine), log), 0);
    return readFileBytes(bsp);
}

std::array<float, 3> arr(Vec3 v) { return {v.x, v.y, v.z}; }

std::vector<Vec3> fibonacciNormals(int count) {
    std::vector<Vec3> out;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int k = 0; k < count; ++k) {
        const double z = 1 - (2 * k + 1) / double(count);
        const double r = std::sqrt(1 - z * z);
        out.push_back({float(r * std::cos(golden * k)), float(r * std::sin(golden * k)), float(z)});
    }
    return out;
}

// Both lit files, the light cache of the one without the world lights in its grid, and the
// compiler's lights and scene for the brute force.
class LitMap {
public:
    explicit LitMap(const MapInputs& in) {
        const fs::path dir = test::tempDir() / ("lightcache_" + in.bsp.stem().string());
        fs::remove_all(dir);
        const std::vector<uint8_t> withLights = lightCopy(in, dir / "full", fastGridOptions(), "-light -fast -nolm -sh -worldlights");
        LightOptions leftOut = fastGridOptions();
        leftOut.shNoWorldLights = true;
        const std::vector<uint8_t> without = lightCopy(in, dir / "cache", leftOut, "-light -fast -nolm -shnoworldlights");
        cacheBytes_ = without;
        error_ = fullGrid_.loadFromBsp(withLights.data(), withLights.size(), "full");
        if (error_.empty()) error_ = cache_.loadFromBsp(without.data(), without.size(), "cache");
        if (!error_.empty()) return;

        Log log(false);
        ctx_.options = leftOut;
        loadLightInputs(ctx_, commonFor(in, dir / "cache" / "maps" / in.bsp.filename(), "-light"), log);
        buildSurfaceGeometry(ctx_);
        buildScene(ctx_);
        createLights(ctx_, log);
        const WorldLightSettings settings = worldLightSettings(ctx_.options);
        for (const Light& light : ctx_.lights)
            if (worldLightRecord(light, settings)) listed_.push_back(&light);
        env_ = surfaceLightingEnv(ctx_);
        env_.settings.forceFast = true;
        if (ctx_.scene) env_.rayMask = ctx_.scene->receiverMask(1);
    }

    const std::string& error() const { return error_; }
    const std::vector<uint8_t>& cacheBytes() const { return cacheBytes_; }
    const sh::LightCache& cache() const { return cache_; }
    size_t listedLights() const { return listed_.size(); }
    bool open(Vec3 p) const { return ctx_.tree->clusterForPoint(p) >= 0 && !ctx_.tree->pointInSolid(p); }

    // Direct light of every listed light, occluded as the compiler occludes a luxel at `p`.
    std::vector<Vec3> bruteForceDirect(Vec3 p, const std::vector<Vec3>& normals) const {
        std::vector<Vec3> out(normals.size());
        const int cluster = ctx_.tree->clusterForPoint(p);
        for (const Light* light : listed_) {
            const std::optional<LightContribution> c = lightToGridPoint(*light, p, cluster, env_);
            if (!c) continue;
            for (size_t k = 0; k < normals.size(); ++k) {
                const float cosine = dot(normals[k], c->direction);
                const float incidence = light->controlled && light->type != LightType::Sun
                                            ? controlledIncidence(*light->controlled, cosine)
                                            : std::max(0.f, cosine);
                out[k] += c->color * (incidence / 255.0f * ctx_.options.gridScale);
            }
        }
        return out;
    }

    struct Errors {
        double shAlone = 0;     // mean over the normals of |SH grid alone - brute force|, RGB summed
        double withCache = 0;   // the same for the grid without the lights plus the light cache
        double truthScale = 0;  // mean |brute force|, for relative figures
    };

    Errors errorsAt(Vec3 p, const std::vector<Vec3>& normals) const {
        const float at[3] = {p.x, p.y, p.z};
        const sh::GridPointSH full = fullGrid_.sample(at);
        const sh::LightCacheResult r = cache_.query(at);
        const sh::GridPointSH rest = cache_.grid().sample(at);
        const std::vector<Vec3> direct = bruteForceDirect(p, normals);
        Errors e;
        for (size_t k = 0; k < normals.size(); ++k) {
            const float n[3] = {normals[k].x, normals[k].y, normals[k].z};
            float fullRgb[3], restRgb[3], probeRgb[3];
            sh::irradianceAt(full, n, fullRgb);
            sh::irradianceAt(rest, n, restRgb);
            sh::irradianceAt(r.probe, n, probeRgb);
            Vec3 cached{probeRgb[0], probeRgb[1], probeRgb[2]};
            for (int i = 0; i < r.localCount; ++i) {
                const auto v = sh::evaluateWorldLight(cache_.lights()[r.local[i].index], arr(p), arr(normals[k]));
                cached += Vec3{v[0], v[1], v[2]};
            }
            const Vec3 truth = direct[k] + Vec3{restRgb[0], restRgb[1], restRgb[2]};
            const Vec3 alone{fullRgb[0], fullRgb[1], fullRgb[2]};
            for (int c = 0; c < 3; ++c) {
                e.shAlone += std::fabs(alone[c] - truth[c]);
                e.withCache += std::fabs(cached[c] - truth[c]);
                e.truthScale += std::fabs(truth[c]);
            }
        }
        e.shAlone /= double(normals.size());
        e.withCache /= double(normals.size());
        e.truthScale /= double(normals.size());
        return e;
    }

    // Distance from `p` to the nearest point or spot light the lump lists.
    float nearestLocalLight(Vec3 p) const {
        float best = INFINITY;
        for (const sh::WorldLight& l : cache_.lights())
            if (l.type != sh::WorldLightType::Sun)
                best = std::min(best, length(p - Vec3{l.origin[0], l.origin[1], l.origin[2]}));
        return best;
    }

private:
    std::string error_;
    std::vector<uint8_t> cacheBytes_;
    sh::GridRuntime fullGrid_;
    sh::LightCache cache_;
    LightContext ctx_;
    std::vector<const Light*> listed_;
    LightingEnv env_;
};

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
    const std::vector<Vec3> normals = fibonacciNormals(kNormals);
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
    const LitMap map(pillarRoom());
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
    const LitMap map(pillarRoom());
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
    const LitMap map(pillarRoom());
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

// oacmpdm1 as shipped, relit: paths from every player start towards every point or spot light
// within 512 units, and between neighbouring starts.
TEST(LightCacheAccuracy, Oacmpdm1PathsHalveTheGridsErrorNearLights) {
    const fs::path shipped = test::realBsp("oacmpdm1");
    fs::path mapSource;
    for (const fs::path& p : test::oacmpMapSources())
        if (p.stem() == "oacmpdm1") mapSource = p;
    ASSERT_FALSE(mapSource.empty()) << "oacmpdm1.map missing from the data cache";
    const LitMap map(MapInputs{shipped, mapSource, {test::openArenaBase().string()}, "baseoa"});
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
