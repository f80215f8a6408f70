// -light -worldlights on the box room of bsp-samples with a point light, a linear light, a
// controlled-model light, a spotlight and a sun: the lump's records, their clusters against the
// BSP's own leaf lookup, their evaluation against the compiler's unoccluded grid contribution,
// the SH grid against the projection of the records, output independent of the thread count, and
// a relight that replaces or removes the lump.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "../light/light_test_util.h"
#include "file_io.h"
#include "light_context.h"
#include "light_contribution.h"
#include "light_stage.h"
#include "sh.h"
#include "sh_grid_lump.h"
#include "test_data.h"
#include "world_lights_export.h"

namespace q3::light {
namespace {

namespace fs = std::filesystem;

// Relative tolerance of a record's evaluation against the compiler's contribution: the two
// compute the same formula with the colour multiplied in at a different step (a few float ulps).
constexpr float kRelativeTolerance = 1e-5f;

fs::path writeLitRoom(const fs::path& dir) {
    bsp::Bsp b = bsp::readBsp(fs::path(Q3MAP_SOURCE_DIR) / "bsp-samples/golden/box_room.bsp");
    std::vector<bsp::Entity> entities = bsp::parseEntities(b.entities, "box_room.bsp");
    std::erase_if(entities, [](const bsp::Entity& e) { return e.value("classname") == "light"; });
    // The room's inside is 0..512 x 0..512 x 0..256.
    entities.push_back(test::entity({{"classname", "light"}, {"origin", "128 128 128"}, {"light", "300"}}));
    entities.push_back(test::entity(
        {{"classname", "light"}, {"origin", "400 100 64"}, {"light", "400"}, {"spawnflags", "1"}, {"_color", "1 0.5 0"}}));
    entities.push_back(test::entity({{"classname", "light"},
                                     {"origin", "100 400 100"},
                                     {"brightness", "0.8"},
                                     {"falloff_end_dist", "350"},
                                     {"_color", "1 0.5 0.25"}}));
    entities.push_back(test::entity(
        {{"classname", "light"}, {"origin", "384 384 200"}, {"light", "500"}, {"target", "spot1"}, {"radius", "64"}}));
    entities.push_back(test::entity({{"classname", "info_null"}, {"targetname", "spot1"}, {"origin", "384 384 0"}}));
    entities.push_back(test::entity(
        {{"classname", "light"}, {"origin", "256 256 200"}, {"light", "100"}, {"_sun", "1"}, {"target", "sun1"}}));
    entities.push_back(test::entity({{"classname", "info_null"}, {"targetname", "sun1"}, {"origin", "300 280 0"}}));
    b.entities = bsp::unparseEntities(entities);
    fs::create_directories(dir / "maps");
    const fs::path path = dir / "maps" / "room.bsp";
    bsp::writeBsp(path, b);
    return path;
}

LightOptions worldLightOptions() {
    LightOptions options;
    options.fast = true;
    options.noLightmaps = true;
    options.sh = true;
    options.worldLights = true;
    options.shExact = true;  // every probe lights every light itself (no interpolation between corners)
    return options;
}

CommonOptions commonFor(const fs::path& bsp, int threads) {
    CommonOptions common;
    common.mapPath = bsp;
    common.threads = threads;
    common.commandLine = "-light -fast -nolm -sh -worldlights";
    return common;
}

std::vector<uint8_t> litLump(const fs::path& bspPath, const LightOptions& options, int threads) {
    Log log(false);
    EXPECT_EQ(runLightStage(options, commonFor(bspPath, threads), log), 0);
    const bsp::Bsp lit = bsp::readBsp(bspPath);
    const bsp::BspxLump* lump = lit.findBspx(sh::kWorldLightsLumpName);
    return lump ? lump->data : std::vector<uint8_t>{};
}

// The cluster of the leaf holding `p`, by the BSP's node tree (front child when on or in front).
int clusterAt(const bsp::Bsp& b, Vec3 p) {
    int node = 0;
    while (node >= 0) {
        const bsp::Node& n = b.nodes[size_t(node)];
        const bsp::Plane& plane = b.planes[size_t(n.planeNum)];
        const float side = plane.normal[0] * p.x + plane.normal[1] * p.y + plane.normal[2] * p.z - plane.dist;
        node = side >= 0 ? n.children[0] : n.children[1];
    }
    return b.leafs[size_t(-node - 1)].cluster;
}

// Suns get records; the many suns of a sky dome are sky ambient and stay in the SH grid unlisted.
TEST(WorldLightRecords, SkyDomeSunsAreNotListed) {
    Light sun;
    sun.type = LightType::Sun;
    sun.photons = 100;
    sun.normal = {0, 0, 1};
    WorldLightSettings settings;
    settings.shGrid = true;
    settings.outOfShGrid = true;
    ASSERT_TRUE(worldLightRecord(sun, settings).has_value());
    EXPECT_TRUE(keptOutOfShGrid(sun, settings));
    sun.skyDome = true;
    EXPECT_FALSE(worldLightRecord(sun, settings).has_value());
    EXPECT_FALSE(keptOutOfShGrid(sun, settings));
}

class WorldLightsCompile : public ::testing::Test {
protected:
    void SetUp() override {
        bspPath_ = writeLitRoom(q3::test::tempDir());
        lump_ = litLump(bspPath_, worldLightOptions(), 2);
        std::string error;
        ASSERT_TRUE(sh::decodeWorldLights(lump_.data(), lump_.size(), records_, error)) << error;
    }
    fs::path bspPath_;
    std::vector<uint8_t> lump_;
    std::vector<sh::WorldLight> records_;
};

TEST_F(WorldLightsCompile, ListsEveryPointSpotAndSunLightWithItsCluster) {
    int points = 0, spots = 0, suns = 0;
    for (const sh::WorldLight& r : records_) {
        points += r.type == sh::WorldLightType::Point;
        spots += r.type == sh::WorldLightType::Spot;
        suns += r.type == sh::WorldLightType::Sun;
        EXPECT_EQ(r.flags, sh::kWorldLightInShGrid);  // -sh ran and every light is style 0
    }
    EXPECT_EQ(points, 3);
    EXPECT_EQ(spots, 1);
    EXPECT_EQ(suns, 1);
    ASSERT_EQ(records_.size(), 5u);
    EXPECT_EQ(lump_.size(), 16u + 5u * 96u);

    const bsp::Bsp lit = bsp::readBsp(bspPath_);
    for (const sh::WorldLight& r : records_) {
        if (r.type == sh::WorldLightType::Sun) {
            EXPECT_EQ(r.cluster, -1);
            continue;
        }
        EXPECT_GE(r.cluster, 0);
        EXPECT_EQ(r.cluster, clusterAt(lit, {r.origin[0], r.origin[1], r.origin[2]}));
    }
    // Each falloff model appears: inverse square, linear (spawnflags 1), controlled, parallel.
    std::vector<sh::WorldLightFalloff> models;
    for (const sh::WorldLight& r : records_) models.push_back(r.falloff);
    for (auto model : {sh::WorldLightFalloff::InverseSquare, sh::WorldLightFalloff::Linear,
                       sh::WorldLightFalloff::Controlled, sh::WorldLightFalloff::Parallel})
        EXPECT_NE(std::find(models.begin(), models.end(), model), models.end()) << int(model);
}

TEST_F(WorldLightsCompile, RecordsEvaluateToTheCompilersUnoccludedContribution) {
    // The lights as the stage made them, paired with their records in order.
    Log log(false);
    LightContext ctx;
    ctx.options = worldLightOptions();
    loadLightInputs(ctx, commonFor(bspPath_, 1), log);
    buildSurfaceGeometry(ctx);
    buildScene(ctx);
    createLights(ctx, log);
    std::vector<const Light*> listed;
    WorldLightSettings settings;
    settings.shGrid = true;
    settings.forceFast = true;
    for (const Light& light : ctx.lights)
        if (worldLightRecord(light, settings)) listed.push_back(&light);
    ASSERT_EQ(listed.size(), records_.size());

    LightingEnv env;  // no scene, no tree: unoccluded and unculled
    env.settings.forceFast = true;
    const Vec3 normals[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                            normalize(Vec3{1, 1, 1}), normalize(Vec3{-1, 2, -0.5f})};
    int compared = 0, lit = 0;
    for (size_t i = 0; i < listed.size(); ++i) {
        const Light& light = *listed[i];
        const sh::WorldLight& record = records_[i];
        for (float x : {32.f, 200.f, 330.f, 480.f})
            for (float y : {40.f, 250.f, 384.f, 470.f})
                for (float z : {16.f, 100.f, 230.f}) {
                    const Vec3 p{x, y, z};
                    const std::optional<LightContribution> c = lightToGridPoint(light, p, -1, env);
                    for (const Vec3& n : normals) {
                        Vec3 expected{};
                        if (c) {
                            const float cosine = dot(n, c->direction);
                            const float incidence =
                                light.controlled && light.type != LightType::Sun
                                    ? controlledIncidence(*light.controlled, cosine)
                                    : std::max(0.f, cosine);
                            expected = c->color * (incidence / 255.0f);
                        }
                        // The controlled incidence jumps from 0 to 1 - w at the terminator: a
                        // normal within rounding of it may fall on either side.
                        if (c && light.controlled && std::fabs(dot(n, c->direction)) < 1e-5f) continue;
                        const auto e = sh::evaluateWorldLight(record, {p.x, p.y, p.z}, {n.x, n.y, n.z});
                        for (int k = 0; k < 3; ++k)
                            EXPECT_NEAR(e[size_t(k)], expected[k], kRelativeTolerance * std::fabs(expected[k]) + 1e-9f)
                                << "light " << i << " at " << x << " " << y << " " << z << " channel " << k << " normal " << n.x << " " << n.y << " " << n.z << " lit " << bool(c);
                        ++compared;
                        lit += expected.x > 0;
                    }
                }
    }
    EXPECT_GT(compared, 5 * 48 * 8 * 9 / 10);  // few normals lie on a terminator
    EXPECT_GT(lit, compared / 5);  // most comparisons are of light that arrives, not of zeros
}

// The records' unit claim, end to end: at an open grid point the SH grid's nine coefficients are
// the projection of the summed record evaluations over all normals (the grid projects each
// light's incidence exactly, so only the quadrature of the kinks at the terminators differs).
// Suns are left out: the sealed room has no sky, so the grid receives none of their light.
TEST_F(WorldLightsCompile, RecordsSumToTheShGridAtOpenPoints) {
    const bsp::Bsp lit = bsp::readBsp(bspPath_);
    sh::GridSH grid;
    std::string error;
    ASSERT_TRUE(sh::decodeGridLump(lit.shGrid.data(), lit.shGrid.size(), grid, error)) << error;
    constexpr int kNormals = 8192;
    std::vector<std::array<float, 3>> normals;
    std::vector<sh::Basis> basis;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int k = 0; k < kNormals; ++k) {
        const double z = 1 - (2 * k + 1) / double(kNormals);
        const double r = std::sqrt(1 - z * z);
        const sh::Vec3d n{r * std::cos(golden * k), r * std::sin(golden * k), z};
        normals.push_back({float(n.x), float(n.y), float(n.z)});
        basis.push_back(sh::evalBasis(n));
    }
    const double weight = 4 * M_PI / kNormals;
    int checked = 0;
    for (int z = 0; z < grid.bounds[2]; ++z)
        for (int y = 0; y < grid.bounds[1]; ++y)
            for (int x = 0; x < grid.bounds[0]; ++x) {
                const std::array<float, 3> p{grid.mins[0] + x * grid.size[0], grid.mins[1] + y * grid.size[1],
                                             grid.mins[2] + z * grid.size[2]};
                // Away from the walls (no nudging, no fill) and on a coarse subset.
                if (p[0] < 64 || p[0] > 448 || p[1] < 64 || p[1] > 448 || p[2] < 48 || p[2] > 208) continue;
                if ((x + y + z) % 5 != 0) continue;
                std::array<std::array<double, 3>, 9> projected{};
                double scale[3] = {0, 0, 0};
                for (const sh::WorldLight& r : records_) {
                    if (r.type == sh::WorldLightType::Sun) continue;
                    const auto arriving = sh::worldLightArriving(r, p);
                    for (int c = 0; c < 3; ++c) scale[c] += std::fabs(arriving[size_t(c)]);
                    for (int k = 0; k < kNormals; ++k) {
                        const auto e = sh::evaluateWorldLight(r, p, normals[size_t(k)]);
                        for (int i = 0; i < 9; ++i)
                            for (int c = 0; c < 3; ++c)
                                projected[size_t(i)][size_t(c)] += e[size_t(c)] * basis[size_t(k)][size_t(i)] * weight;
                    }
                }
                const auto& stored = grid.points[size_t(x + y * grid.bounds[0] + z * grid.bounds[0] * grid.bounds[1])];
                for (int i = 0; i < 9; ++i)
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(stored.coeffs[i][c], projected[size_t(i)][size_t(c)], 0.002 * scale[c] + 1e-6)
                            << "point " << p[0] << " " << p[1] << " " << p[2] << " coefficient " << i << " channel " << c;
                ++checked;
            }
    EXPECT_GE(checked, 20);
}

// -shnoworldlights: the same records, none flagged as in the SH grid, the legacy grid untouched, and
// an SH grid without their direct light. Every light of the room is listed and the room has no
// ambient, so that grid is black where the full one is lit.
TEST_F(WorldLightsCompile, ShNoWorldLightsLeavesTheListedLightsOutOfTheShGrid) {
    const bsp::Bsp full = bsp::readBsp(bspPath_);
    LightOptions options = worldLightOptions();
    options.shNoWorldLights = true;
    const std::vector<uint8_t> lump = litLump(bspPath_, options, 2);
    std::vector<sh::WorldLight> records;
    std::string error;
    ASSERT_TRUE(sh::decodeWorldLights(lump.data(), lump.size(), records, error)) << error;
    ASSERT_EQ(records.size(), records_.size());
    for (size_t i = 0; i < records.size(); ++i) {
        EXPECT_EQ(records[i].flags, 0u);
        sh::WorldLight flagged = records[i];
        flagged.flags = records_[i].flags;
        EXPECT_EQ(sh::encodeWorldLights(std::span(&flagged, 1)), sh::encodeWorldLights(std::span(&records_[i], 1)));
    }
    const bsp::Bsp left = bsp::readBsp(bspPath_);
    ASSERT_EQ(left.lightGrid.size(), full.lightGrid.size());
    EXPECT_EQ(std::memcmp(left.lightGrid.data(), full.lightGrid.data(), full.lightGrid.size() * sizeof(bsp::GridPoint)), 0);
    sh::GridSH fullGrid, leftGrid;
    ASSERT_TRUE(sh::decodeGridLump(full.shGrid.data(), full.shGrid.size(), fullGrid, error)) << error;
    ASSERT_TRUE(sh::decodeGridLump(left.shGrid.data(), left.shGrid.size(), leftGrid, error)) << error;
    ASSERT_EQ(leftGrid.points.size(), fullGrid.points.size());
    double fullSum = 0, leftSum = 0;
    for (size_t i = 0; i < fullGrid.points.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            fullSum += std::fabs(fullGrid.points[i].coeffs[0][c]);
            leftSum += std::fabs(leftGrid.points[i].coeffs[0][c]);
        }
    EXPECT_GT(fullSum, 1.0);
    EXPECT_EQ(leftSum, 0.0);
}

TEST_F(WorldLightsCompile, ThreadCountAndRelight) {
    EXPECT_EQ(litLump(bspPath_, worldLightOptions(), 1), lump_);
    // A relight without -sh keeps the lights but no longer says they are in the grid.
    LightOptions noSh = worldLightOptions();
    noSh.sh = false;
    const std::vector<uint8_t> without = litLump(bspPath_, noSh, 2);
    std::vector<sh::WorldLight> records;
    std::string error;
    ASSERT_TRUE(sh::decodeWorldLights(without.data(), without.size(), records, error)) << error;
    ASSERT_EQ(records.size(), records_.size());
    for (const sh::WorldLight& r : records) EXPECT_EQ(r.flags, 0u);
    EXPECT_EQ(bsp::readBsp(bspPath_).bspx.size(), 1u);  // replaced in place, not appended
    // Without -worldlights the old lump goes.
    LightOptions none = worldLightOptions();
    none.worldLights = false;
    EXPECT_TRUE(litLump(bspPath_, none, 2).empty());
}

}  // namespace
}  // namespace q3::light
