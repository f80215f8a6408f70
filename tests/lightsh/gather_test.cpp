// -shgather: the direction set, the reflected radiance of a lit floor against the closed form, and the
// whole -light stage on a room lit only by an area light on its ceiling: probes near the floor get
// the floor's colour from below with -shgather and not without it, nothing is counted twice (a
// black floor adds exactly nothing), and the output does not depend on the thread count; and a real
// map, where the gather only ever adds light.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "../light/light_test_util.h"
#include "file_io.h"
#include "grid_sh.h"
#include "grid_sh_gather.h"
#include "image.h"
#include "light_context.h"
#include "light_stage.h"
#include "option_parser.h"
#include "sh_grid_lump.h"
#include "bsp_scene.h"
#include "test_data.h"

namespace q3::light {
namespace {

TEST(ShGather, DirectionsAreUnitAndBalanced) {
    for (int n : {16, 64, 256, 1000}) {
        const std::vector<Vec3> d = gatherDirections(n);
        ASSERT_EQ(d.size(), size_t(n));
        Vec3 sum;
        double zz = 0;
        for (const Vec3& v : d) {
            EXPECT_NEAR(length(v), 1.0f, 1e-5f);
            sum += v;
            zz += double(v.z) * v.z;
        }
        // Equal-area set: mean direction ~ 0 and E[z^2] ~ 1/3.
        EXPECT_LT(length(sum) / n, 0.02f) << n;
        EXPECT_NEAR(zz / n, 1.0 / 3.0, 0.01) << n;
        EXPECT_EQ(d, gatherDirections(n));  // fixed pattern
    }
}

LightOptions parseLightArgs(std::vector<std::string> args) {
    LightOptions options;
    cli::parseOptions(lightOptionTable(), args, cli::ParseContext{"-light", {}, {}}, options);
    return options;
}

TEST(ShGather, OptionsImplySh) {
    EXPECT_FALSE(parseLightArgs({}).shGather);
    EXPECT_EQ(parseLightArgs({}).shGatherSamples, 64);
    EXPECT_EQ(parseLightArgs({}).shGatherStep, 2);
    EXPECT_EQ(parseLightArgs({"-shgatherstep", "1"}).shGatherStep, 1);
    for (const char* bad : {"0", "9", "x"})
        EXPECT_THROW(parseLightArgs({"-shgatherstep", bad}), cli::UsageError) << bad;
    const LightOptions o = parseLightArgs({"-shgather", "-shgathersamples", "128"});
    EXPECT_TRUE(o.shGather);
    EXPECT_TRUE(o.sh);
    EXPECT_EQ(o.shGatherSamples, 128);
    for (const char* bad : {"0", "15", "-3", "x", "70000"})
        EXPECT_THROW(parseLightArgs({"-shgathersamples", bad}), cli::UsageError) << bad;
}

// A context holding one large floor (z = 0, facing up) with uniform baked light `light` and an
// albedo without image, plus optionally a sky over it.
struct FloorScene {
    LightContext ctx;
    LightingShader skyShader;
    std::vector<ShaderAlbedo> albedo;
    FloorScene(Vec3 light, Vec3 color, bool withSky) {
        skyShader.sky = true;
        ctx.surfaces.push_back(test::quad({-20000, -20000, 0}, {40000, 0, 0}, {0, 40000, 0}));
        ctx.surfaces.back().surfaceNum = 0;
        bsp::Surface floor{};
        floor.shaderNum = 0;
        ctx.bsp.surfaces.push_back(floor);
        BakedSurfaceLight baked;
        baked.width = baked.height = 1;
        baked.color = {light};
        baked.vertexCoords.assign(4, {0.5f, 0.5f});
        ctx.bakedLight.push_back(baked);
        if (withSky) {
            ctx.surfaces.push_back(test::quad({-20000, -20000, 500}, {40000, 0, 0}, {0, 40000, 0}, &skyShader, 0));
            ctx.surfaces.back().surfaceNum = 1;
            bsp::Surface sky{};
            sky.shaderNum = 1;
            ctx.bsp.surfaces.push_back(sky);
        }
        albedo.push_back(ShaderAlbedo{nullptr, color});
        albedo.push_back(ShaderAlbedo{nullptr, {1, 1, 1}});
    }
};

TEST(ShGather, LitFloorReflectsAlbedoTimesLight) {
    // A floor filling the lower hemisphere with radiance L = albedo * E / (pi * 255) gives the
    // irradiance pi * L = albedo * E / 255 towards -Z and 0 towards +Z; the L2 projection of a
    // uniform hemisphere is exact at the poles. Tolerance: 1% (sampling, finite floor).
    const Vec3 light{200, 150, 100}, color{0.8f, 0.4f, 0.2f};
    FloorScene floor(light, color, true);
    const GatherScene scene(floor.ctx, floor.albedo);
    const std::vector<Vec3> directions = gatherDirections(4096);
    const sh::SH9Color e = gatherProbe(scene, {3, -5, 64}, directions);
    const sh::Rgb down = sh::evalIrradiance(e, {0, 0, -1}), up = sh::evalIrradiance(e, {0, 0, 1});
    EXPECT_NEAR(down.r, 0.8 * 200 / 255.0, 0.01 * 0.8 * 200 / 255.0);
    EXPECT_NEAR(down.g, 0.4 * 150 / 255.0, 0.01 * 0.4 * 150 / 255.0);
    EXPECT_NEAR(down.b, 0.2 * 100 / 255.0, 0.01 * 0.2 * 100 / 255.0);
    EXPECT_NEAR(up.r, 0, 0.01 * 0.8 * 200 / 255.0);  // the sky above is direct light: not gathered
    // Sideways: half of it.
    EXPECT_NEAR(sh::evalIrradiance(e, {1, 0, 0}).r, 0.5 * 0.8 * 200 / 255.0, 0.02 * 0.8 * 200 / 255.0);
    // Radiance of one ray straight down, and nothing from the sky straight up.
    const sh::Rgb l = scene.radianceAlong({0, 0, 64}, {0, 0, -1});
    EXPECT_NEAR(l.r, 0.8 * 200 / (sh::kPi * 255), 1e-6);
    const sh::Rgb skyward = scene.radianceAlong({0, 0, 64}, {0, 0, 1});
    EXPECT_EQ(skyward.r + skyward.g + skyward.b, 0);
}

TEST(ShGather, TexelAlbedoAtTheHit) {
    // A 2 x 1 image, red texel then blue texel; nearest lookup as q3map2 (x = int(2s + 0.5) mod 2), so
    // s = 0.1 (x = -16000) is red and s = 0.6 (x = 4000) is blue; the quad's s goes 0..1 along X.
    FloorScene floor({255, 255, 255}, {0.5f, 0.5f, 0.5f}, false);
    LightImage image;
    image.width = 2;
    image.height = 1;
    image.rgba = {255, 0, 0, 255, 0, 0, 255, 255};
    floor.albedo[0].image = &image;
    const GatherScene scene(floor.ctx, floor.albedo);
    const sh::Rgb left = scene.radianceAlong({-16000, 0, 10}, {0, 0, -1});
    const sh::Rgb right = scene.radianceAlong({4000, 0, 10}, {0, 0, -1});
    EXPECT_GT(left.r, 0);
    EXPECT_EQ(left.b, 0);
    EXPECT_GT(right.b, 0);
    EXPECT_EQ(right.r, 0);
}

TEST(ShGather, PatchHitsReadTheirOwnLuxel) {
    // A flat 3 x 3 patch over x, y in 0..256 at z = 0 with a 4 x 1 lightmap: red luxels on the low-x
    // half, blue on the high-x half. Luxel x = 1.5 * control column + 0.5, control column = x / 128.
    LightContext ctx;
    bsp::Surface patchSurface{};
    patchSurface.surfaceType = bsp::MST_PATCH;
    patchSurface.patchWidth = patchSurface.patchHeight = 3;
    patchSurface.numVerts = 9;
    for (int v = 0; v < 9; ++v) {
        bsp::DrawVert dv{};
        dv.xyz[0] = 128.0f * float(v % 3);
        dv.xyz[1] = 128.0f * float(v / 3);
        dv.normal[2] = 1;
        ctx.bsp.drawVerts.push_back(dv);
    }
    ctx.bsp.surfaces.push_back(patchSurface);
    bsp::Model world{};
    world.numSurfaces = 1;
    ctx.bsp.models.push_back(world);
    ctx.entities.push_back(test::entity({{"classname", "worldspawn"}}));
    buildSurfaceGeometry(ctx);
    ASSERT_TRUE(ctx.surfaces[0].isPatch);
    BakedSurfaceLight baked;
    baked.width = 4;
    baked.height = 1;
    baked.color = {{255, 0, 0}, {255, 0, 0}, {0, 0, 255}, {0, 0, 255}};
    ctx.bakedLight.push_back(baked);
    const std::vector<ShaderAlbedo> albedo{ShaderAlbedo{nullptr, {1, 1, 1}}};
    const GatherScene scene(ctx, albedo);
    const sh::Rgb low = scene.radianceAlong({20, 128, 10}, {0, 0, -1});   // luxel 0.73 -> 0
    const sh::Rgb high = scene.radianceAlong({236, 128, 10}, {0, 0, -1}); // luxel 3.27 -> 3
    EXPECT_NEAR(low.r, 1 / sh::kPi, 1e-6);
    EXPECT_EQ(low.b, 0);
    EXPECT_NEAR(high.b, 1 / sh::kPi, 1e-6);
    EXPECT_EQ(high.r, 0);
}

// ---- The whole stage on a room built in the test ----------------------------------------------

using q3::test::addQuad;

// A 256 x 256 floor at z = 8 (texture `floorRgb`) under a ceiling light at z = 248 facing down; the
// game folder is <dir>/baseq3 with the shader script and the floor texture.
std::filesystem::path writeRoom(const std::filesystem::path& dir, std::array<uint8_t, 3> floorRgb) {
    const std::filesystem::path game = dir / "baseq3";
    std::filesystem::create_directories(game / "maps");
    std::filesystem::create_directories(game / "scripts");
    std::filesystem::create_directories(game / "textures" / "gather");
    const std::string script =
        "textures/gather/light\n{\n  q3map_surfacelight 4000\n  q3map_lightRGB 1 1 1\n}\n"
        "textures/gather/floor\n{\n  { map $lightmap }\n}\n";
    writeFileAtomic(game / "scripts" / "gather.shader", std::vector<uint8_t>(script.begin(), script.end()));
    Image floorImage;
    floorImage.width = floorImage.height = 4;
    for (int i = 0; i < 16; ++i)
        for (uint8_t v : {floorRgb[0], floorRgb[1], floorRgb[2], uint8_t(255)}) floorImage.rgba.push_back(v);
    writeFileAtomic(game / "textures" / "gather" / "floor.tga", encodeTga(floorImage, false));

    bsp::Bsp b;
    b.version = bsp::kVersionQ3;
    b.headerLumps = 18;
    for (const char* name : {"textures/gather/floor", "textures/gather/light"}) {
        bsp::Shader shader{};
        std::strcpy(shader.name, name);
        shader.contentFlags = 1;
        b.shaders.push_back(shader);
    }
    addQuad(b, {0, 0, 8}, {0, 256, 0}, {256, 0, 0}, 0);     // floor, normal +z
    addQuad(b, {0, 0, 248}, {0, 256, 0}, {256, 0, 0}, 1);   // ceiling light, emitting downwards
    bsp::Model world{};
    world.maxs[0] = world.maxs[1] = 256;
    world.maxs[2] = 256;
    world.numSurfaces = int32_t(b.surfaces.size());
    b.models.push_back(world);
    std::vector<bsp::Entity> ents(1);
    ents[0].pairs = {{"classname", "worldspawn"}};
    b.entities = bsp::unparseEntities(ents);
    const std::filesystem::path path = game / "maps" / "room.bsp";
    writeFileAtomic(path, bsp::serializeBsp(b));
    return path;
}

void lightRoom(const std::filesystem::path& path, const LightOptions& options, int threads = 1) {
    CommonOptions common;
    common.mapPath = path;
    common.threads = threads;
    common.commandLine = "-light room.bsp";
    Log log(false);
    EXPECT_EQ(runLightStage(options, common, log), 0);
}

sh::GridSH runRoom(const std::filesystem::path& path, bool gather, int threads = 1) {
    LightOptions options;
    options.sh = true;
    options.shGather = gather;
    options.gridSizeSH[0] = options.gridSizeSH[1] = options.gridSizeSH[2] = 64;
    lightRoom(path, options, threads);
    const bsp::Bsp lit = bsp::readBsp(path);
    sh::GridSH grid;
    std::string err;
    EXPECT_TRUE(sh::decodeGridLump(lit.shGrid.data(), lit.shGrid.size(), grid, err)) << err;
    return grid;
}

TEST(ShGatherStage, FloorColouredLightFromBelowOnlyWithGather) {
    const std::filesystem::path dir = q3::test::tempDir();
    const std::filesystem::path plainPath = writeRoom(dir / "plain", {200, 40, 40});
    const std::filesystem::path gatherPath = writeRoom(dir / "gather", {200, 40, 40});
    const sh::GridSH plain = runRoom(plainPath, false);
    const sh::GridSH gathered = runRoom(gatherPath, true);
    ASSERT_EQ(plain.points.size(), gathered.points.size());
    ASSERT_EQ(plain.bounds[2], 5);  // z = 0, 64, ..., 256

    // Probe (128, 128, 64): 56 units over the middle of the floor.
    const size_t i = size_t(2) + size_t(2) * size_t(plain.bounds[0]) + size_t(1) * plain.bounds[0] * plain.bounds[1];
    const sh::SH9Color p = sh::fromGridPoint(plain.points[i]), g = sh::fromGridPoint(gathered.points[i]);
    const sh::Rgb plainDown = sh::evalIrradianceClamped(p, {0, 0, -1});
    const sh::Rgb gatherDown = sh::evalIrradianceClamped(g, {0, 0, -1});
    const sh::Rgb plainUp = sh::evalIrradiance(p, {0, 0, 1}), gatherUp = sh::evalIrradiance(g, {0, 0, 1});
    ASSERT_GT(plainUp.r, 0.2) << "the ceiling light reaches the probe";
    // Plain -sh sees nothing below (no bounce): at most the L2 ringing of the light above.
    EXPECT_LT(plainDown.r, 0.1 * plainUp.r);
    // With -shgather: clearly lit from below, in the floor's colour (texture 200 40 40, white light).
    EXPECT_GT(gatherDown.r, plainDown.r + 0.1 * plainUp.r);
    const double addedR = sh::evalIrradiance(g, {0, 0, -1}).r - sh::evalIrradiance(p, {0, 0, -1}).r;
    const double addedG = sh::evalIrradiance(g, {0, 0, -1}).g - sh::evalIrradiance(p, {0, 0, -1}).g;
    EXPECT_GT(addedR, 0);
    EXPECT_NEAR(addedR / addedG, 5.0, 0.25);
    // The direct light from above is not counted again: towards +Z the gather adds only the small
    // part of the floor's light that reaches an upward normal through L2 ringing.
    EXPECT_LT(std::abs(gatherUp.r - plainUp.r), 0.05 * plainUp.r);
}

TEST(ShGatherStage, BlackFloorAddsExactlyNothing) {
    // Every surface the rays can hit reflects nothing (black floor; the ceiling is only an emitter
    // and receives no light): the gathered grid must equal the plain one bit for bit, which shows
    // that neither the ceiling light's emission nor its direct light is gathered a second time.
    const std::filesystem::path dir = q3::test::tempDir();
    const sh::GridSH plain = runRoom(writeRoom(dir / "plain", {0, 0, 0}), false);
    const sh::GridSH gathered = runRoom(writeRoom(dir / "gather", {0, 0, 0}), true);
    ASSERT_EQ(plain.points.size(), gathered.points.size());
    for (size_t i = 0; i < plain.points.size(); ++i)
        EXPECT_EQ(std::memcmp(&plain.points[i], &gathered.points[i], sizeof(sh::GridPointSH)), 0) << "point " << i;
}

// Relighting without -sh leaves no SH grid of the earlier run behind, in lump 18 or as BSPX: the
// file equals a fresh BSP lit without -sh.
TEST(ShStage, RelightWithoutShDropsTheEarlierGrid) {
    const std::filesystem::path dir = q3::test::tempDir();
    auto light = [](const std::filesystem::path& path, bool sh, bool bspx) {
        LightOptions options;
        options.sh = sh;
        options.shBspx = bspx;
        lightRoom(path, options);
    };
    const std::filesystem::path fresh = writeRoom(dir / "fresh", {90, 90, 90});
    light(fresh, false, false);
    for (bool bspx : {false, true}) {
        const std::filesystem::path relit = writeRoom(dir / (bspx ? "bspx" : "lump18"), {90, 90, 90});
        light(relit, true, bspx);
        const bsp::Bsp withSh = bsp::readBsp(relit);
        ASSERT_EQ(withSh.shGrid.empty(), bspx);
        ASSERT_EQ(withSh.findBspx(sh::kBspxLumpName) != nullptr, bspx);
        light(relit, false, false);
        bsp::Bsp without = bsp::readBsp(relit);
        EXPECT_TRUE(without.shGrid.empty());
        EXPECT_EQ(without.findBspx(sh::kBspxLumpName), nullptr);
        EXPECT_EQ(without.version, bsp::kVersionQ3);
        // The same file but for the command lines the entity lump records.
        const bsp::Bsp freshBsp = bsp::readBsp(fresh);
        without.entities = freshBsp.entities;
        // writeRoom's header has 18 entries where -bsp writes 17; a version 46 file written after the
        // SH grid left has the 17 of -bsp.
        EXPECT_EQ(without.headerLumps, 17);
        without.headerLumps = freshBsp.headerLumps;
        EXPECT_EQ(bsp::serializeBsp(without), bsp::serializeBsp(freshBsp)) << (bspx ? "BSPX" : "lump 18");
    }
}

TEST(ShGatherStage, ThreadCountDoesNotChangeOutput) {
    const std::filesystem::path dir = q3::test::tempDir();
    const std::filesystem::path one = writeRoom(dir / "one", {120, 200, 60});
    const std::filesystem::path two = writeRoom(dir / "two", {120, 200, 60});
    runRoom(one, true, 1);
    runRoom(two, true, 2);
    EXPECT_EQ(readFileBytes(one), readFileBytes(two));
}

// A real map (oacmpdm1 with its shaders and textures; -nolm, so every hit reads vertex colours):
// the gather only adds light (the uniform band of every free probe grows or stays), it adds a
// visible amount on average, and solid points are refilled.
// Mean |difference| of the uniform band between -shgatherstep 2 and 1, relative to the mean
// indirect light, measured at 32 rays per probe on oacmpdm1: 0.31 (the ray noise of the two runs
// included; 0.15 before the light stage followed q3map2 2.5.17n's vertex light, backsplash and
// grid occlusion, which changed both the colours the rays read and the direct grid); the bound
// leaves room above it.
constexpr double kMaxStepTwoDifference = 0.35;

TEST(ShGatherRealMap, AddsNonNegativeIndirectLight) {
    const std::filesystem::path dir = q3::test::tempDir();
    const std::filesystem::path maps = dir / "baseoa" / "maps";
    std::filesystem::create_directories(maps);
    std::filesystem::copy_file(q3::test::realBsp("oacmpdm1"), maps / "oacmpdm1.bsp");
    CommonOptions common;
    common.mapPath = maps / "oacmpdm1.bsp";
    common.basePaths = {q3::test::openArenaBase().string()};
    common.fsGame = "baseoa";
    common.threads = 2;
    common.commandLine = "-light -fast -nolm -shgather maps/oacmpdm1.bsp";
    Log log(false);
    LightContext ctx;
    ctx.options.fast = true;
    ctx.options.noLightmaps = true;
    ctx.options.sh = ctx.options.shGather = true;
    ctx.options.shGatherSamples = 32;
    loadLightInputs(ctx, common, log);
    buildSurfaceGeometry(ctx);
    buildScene(ctx);
    createLights(ctx, log);
    lightVertexes(ctx, log);
    const ShGridLayout layout = setupGridSH(ctx, log);
    ShTraceStats stats;
    sh::GridLumpImage gatheredImage = traceGridSH(ctx, layout, log, &stats);
    const sh::GridSH direct = gatheredImage.decode();
    std::vector<LightImage> images;
    const std::vector<ShaderAlbedo> albedo = loadShaderAlbedo(ctx, images, log);
    size_t withImage = 0;
    for (const ShaderAlbedo& a : albedo) withImage += a.image ? 1 : 0;
    EXPECT_GT(withImage, albedo.size() / 2) << "most shaders of a real map have a texture";
    const ShGatherStats g = gatherIndirectSH(ctx, albedo, gatheredImage, stats, log);
    const sh::GridSH gathered = gatheredImage.decode();
    // -shgatherstep 2 (the default): an eighth of the probes trace, plus those next to solid.
    EXPECT_EQ(g.probes + g.interpolated, stats.points - stats.inSolid);
    EXPECT_LT(g.probes, (stats.points - stats.inSolid) / 2);
    EXPECT_EQ(g.rays, g.probes * 32);

    // Against every probe tracing: the interpolated indirect light stays close on average.
    ctx.options.shGatherStep = 1;
    sh::GridLumpImage everyProbeImage = sh::GridLumpImage::encode(direct);
    const ShGatherStats all = gatherIndirectSH(ctx, albedo, everyProbeImage, stats, log);
    const sh::GridSH everyProbe = everyProbeImage.decode();
    EXPECT_EQ(all.probes, stats.points - stats.inSolid);
    EXPECT_EQ(all.interpolated, 0u);
    double difference = 0, indirect = 0;
    for (size_t i = 0; i < direct.points.size(); ++i)
        for (int ch = 0; ch < 3; ++ch) {
            const double d = direct.points[i].coeffs[0][ch];
            difference += std::abs(double(gathered.points[i].coeffs[0][ch]) - everyProbe.points[i].coeffs[0][ch]);
            indirect += everyProbe.points[i].coeffs[0][ch] - d;
        }
    EXPECT_LT(difference / indirect, kMaxStepTwoDifference);
    double added = 0, total = 0;
    for (size_t i = 0; i < direct.points.size(); ++i) {
        if (stats.solid[i]) continue;
        for (int ch = 0; ch < 3; ++ch) {
            const double d = direct.points[i].coeffs[0][ch], e = gathered.points[i].coeffs[0][ch];
            ASSERT_GE(e, d - 1e-5 * (1 + std::abs(d))) << "point " << i;
            added += e - d;
            total += d;
        }
    }
    EXPECT_GT(added, 0.02 * total) << "indirect light is a visible part of a real map's light";
    EXPECT_LT(added, total) << "one bounce stays below the direct light";
}

}  // namespace
}  // namespace q3::light
