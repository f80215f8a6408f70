// The light stage's preparation steps on a real OpenArena map, and the shader bridge.
#include <gtest/gtest.h>

#include <algorithm>

#include "file_io.h"
#include "grid_encode.h"
#include "light_stage.h"
#include "light_context.h"
#include "map_file.h"
#include "shader_info.h"
#include "shader_loader.h"
#include "vfs.h"
#include "test_data.h"

namespace q3::light {
namespace {

TEST(LightShaders, BridgeCopiesLightingDirectives) {
    ShaderInfo info = makeImplicitShader("textures/test/sky");
    info.compileFlags |= compileflags::Sky;
    ShaderSun sun;
    sun.color = {1, 0.5f, 0.25f};
    sun.intensity = 120;
    sun.direction = normalize(Vec3{1, 0, 1});
    sun.devianceDegrees = 2;
    sun.samples = 8;
    sun.style = 0;
    info.suns.push_back(sun);
    ShaderSkyLight sky;
    sky.value = 50;
    sky.iterations = 4;
    sky.horizonMin = -90;
    info.skyLights.push_back(sky);
    info.surfaceLight = 300;
    info.lightRGB = Vec3{0.2f, 1, 0.4f};
    info.lightSubdivide = 64;
    info.twoSided = true;
    info.backsplashSet = true;
    info.backsplashFraction = 0.1f;
    info.backsplashDistance = 12;

    LightingShader s = toLightingShader(info, nullptr);
    EXPECT_TRUE(s.sky);
    EXPECT_TRUE(s.twoSided);
    ASSERT_EQ(s.suns.size(), 1u);
    EXPECT_FLOAT_EQ(s.suns[0].intensity, 120);
    EXPECT_EQ(s.suns[0].direction, sun.direction);
    EXPECT_FLOAT_EQ(s.suns[0].devianceDeg, 2);
    EXPECT_EQ(s.suns[0].samples, 8);
    ASSERT_EQ(s.skyLights.size(), 1u);
    EXPECT_FLOAT_EQ(s.skyLights[0].horizonMin, -90);
    EXPECT_FLOAT_EQ(s.surfaceLight, 300);
    EXPECT_EQ(s.color, (Vec3{0.2f, 1, 0.4f}));
    EXPECT_TRUE(s.hasLightRGB);
    EXPECT_FLOAT_EQ(s.lightSubdivide, 64);
    EXPECT_TRUE(s.backsplashSet);
    EXPECT_FLOAT_EQ(s.backsplashDistance, 12);

    // Without lightRGB the colour is the light image's average, normalised.
    info.lightRGB.reset();
    LightImage img;
    img.width = 2;
    img.height = 1;
    img.rgba = {200, 100, 0, 255, 100, 50, 0, 255};
    LightingShader fromImage = toLightingShader(info, &img);
    EXPECT_NEAR(fromImage.color.x, 1.0f, 1e-6);
    EXPECT_NEAR(fromImage.color.y, 0.5f, 1e-6);
    EXPECT_EQ(fromImage.color.z, 0.0f);
    EXPECT_EQ(fromImage.lightImage, &img);
}

TEST(LightShaders, LightImageWithTwoDotsIsLoadedByItsFullName) {
    // base_light.shader: ceil1_30_110k names "q3map_lightimage textures/base_light/ceil1_30.blend.tga";
    // q3map2 drops only ".tga", so the light takes the blend image's colour (about 0.45 0.55 1),
    // not ceil1_30.tga's (about 0.62 0.69 1).
    VfsOptions options;
    options.basePaths = {test::openArenaBase()};
    options.gameDirs = {"baseoa"};
    Log log(false);
    Vfs vfs(options, log);
    ShaderTable table = loadShaderTable(vfs, log);
    bsp::Bsp bsp;
    bsp::Shader record{};
    const std::string name = "textures/base_light/ceil1_30_110k";
    std::copy(name.begin(), name.end(), record.name);
    bsp.shaders.push_back(record);
    LightingShaderSet set = resolveLightingShaders(bsp, table, &vfs, log);
    ASSERT_EQ(set.shaders.size(), 1u);
    const LightingShader& s = set.shaders[0];
    EXPECT_FLOAT_EQ(s.surfaceLight, 110000);
    EXPECT_NEAR(s.color.x, 34.26f / 76.70f, 0.01f);
    EXPECT_NEAR(s.color.y, 42.14f / 76.70f, 0.01f);
    EXPECT_FLOAT_EQ(s.color.z, 1.0f);
}

TEST(LightRealData, OacmpDm1LightsSceneAndGrid) {
    const std::filesystem::path dir = test::tempDir();
    std::filesystem::create_directories(dir / "maps");
    std::filesystem::copy_file(test::realBsp("oacmpdm1"), dir / "maps" / "oacmpdm1.bsp");
    std::filesystem::path mapSource;
    for (const auto& p : test::oacmpMapSources())
        if (p.stem() == "oacmpdm1") mapSource = p;
    ASSERT_FALSE(mapSource.empty());
    std::filesystem::copy_file(mapSource, dir / "maps" / "oacmpdm1.map");

    CommonOptions common;
    common.mapPath = dir / "maps" / "oacmpdm1.bsp";
    common.basePaths = {test::openArenaBase().string()};
    common.fsGame = "baseoa";
    common.threads = 2;
    Log log(false);
    LightContext ctx;
    loadLightInputs(ctx, common, log);

    const map::MapFile source = map::loadMap(mapSource);
    EXPECT_EQ(ctx.mapLights.size(), map::lightEntities(source).size());
    EXPECT_GT(ctx.mapLights.size(), 100u);
    ASSERT_EQ(ctx.shaders.shaders.size(), ctx.bsp.shaders.size());
    const bool anySurfaceLight = std::any_of(ctx.shaders.shaders.begin(), ctx.shaders.shaders.end(),
                                             [](const LightingShader& s) { return s.surfaceLight > 0; });
    EXPECT_TRUE(anySurfaceLight);

    buildSurfaceGeometry(ctx);
    buildScene(ctx);
    EXPECT_GT(ctx.scene->casterCount(), 1000u);
    createLights(ctx, log);
    size_t points = 0, areas = 0;
    for (const Light& l : ctx.lights) {
        points += l.type == LightType::Point;
        areas += l.type == LightType::Area;
        if (l.type != LightType::Sun) {
            EXPECT_GE(l.cluster, 0);
        }
    }
    EXPECT_GT(points, 100u);
    EXPECT_GT(areas, 0u);

    lightGrid(ctx, log);
    const GridLayout layout = computeGridLayout(parseGridSize(ctx.entities[0].value("gridsize"), "test"), ctx.bsp);
    ASSERT_EQ(static_cast<int>(ctx.bsp.lightGrid.size()), layout.numPoints());
    // Points in the open are lit (the engine skips points whose ambient is zero).
    size_t lit = 0;
    for (const bsp::GridPoint& p : ctx.bsp.lightGrid)
        if (p.ambient[0] + p.ambient[1] + p.ambient[2] > 0) ++lit;
    EXPECT_GT(lit, ctx.bsp.lightGrid.size() / 2);
    EXPECT_LE(lit + ctx.stats.gridPointsInSolid, ctx.bsp.lightGrid.size());
}

TEST(LightRealData, OacmpDm1SameBytesWithOneAndTwoThreads) {
    const std::filesystem::path dir = test::tempDir();
    std::filesystem::path mapSource;
    for (const auto& p : test::oacmpMapSources())
        if (p.stem() == "oacmpdm1") mapSource = p;
    ASSERT_FALSE(mapSource.empty());
    std::vector<std::vector<uint8_t>> outputs;
    for (int threads : {1, 2}) {
        const std::filesystem::path maps = dir / std::to_string(threads) / "maps";
        std::filesystem::create_directories(maps);
        std::filesystem::copy_file(test::realBsp("oacmpdm1"), maps / "oacmpdm1.bsp");
        std::filesystem::copy_file(mapSource, maps / "oacmpdm1.map");
        CommonOptions common;
        common.mapPath = maps / "oacmpdm1.bsp";
        common.basePaths = {test::openArenaBase().string()};
        common.fsGame = "baseoa";
        common.threads = threads;
        common.commandLine = "-light -fast oacmpdm1.bsp";
        LightOptions options;
        options.fast = true;
        Log log(false);
        ASSERT_EQ(runLightStage(options, common, log), 0);
        outputs.push_back(readFileBytes(common.mapPath));
    }
    EXPECT_EQ(outputs[0], outputs[1]);
    const bsp::Bsp lit = bsp::parseBsp(outputs[0], "oacmpdm1.bsp");
    EXPECT_FALSE(lit.lightmaps.empty());
}

}  // namespace
}  // namespace q3::light
