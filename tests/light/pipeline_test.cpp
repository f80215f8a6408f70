// The whole -light stage on small BSPs built by the test: luxel and grid values against the
// formulas, occlusion by other surfaces, and output that does not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstring>

#include "color_pipeline.h"
#include "file_io.h"
#include "grid_encode.h"
#include "light_context.h"
#include "light_stage.h"
#include "lightmap_layout.h"
#include "surface_lighting.h"
#include "bsp_scene.h"
#include "test_data.h"

namespace q3::light {
namespace {

using q3::test::addQuad;

// A floor 128 x 128 at z = 0 (facing up), a small opaque table at z = 50 over its middle, a point
// light at (64, 64, 100); no BSP tree (every point is in the open).
bsp::Bsp makeRoom() {
    bsp::Bsp b;
    b.version = bsp::kVersionQ3;
    b.headerLumps = 18;
    bsp::Shader sh{};
    std::strcpy(sh.name, "textures/test/floor");
    sh.contentFlags = 1;
    b.shaders.push_back(sh);
    addQuad(b, {0, 0, 0}, {0, 128, 0}, {128, 0, 0}, 0);    // floor, normal +z
    addQuad(b, {48, 48, 50}, {0, 32, 0}, {32, 0, 0}, 0);   // table top, normal +z
    bsp::Model world{};
    world.mins[0] = world.mins[1] = world.mins[2] = 0;
    world.maxs[0] = world.maxs[1] = 128;
    world.maxs[2] = 256;
    world.firstSurface = 0;
    world.numSurfaces = static_cast<int32_t>(b.surfaces.size());
    b.models.push_back(world);
    std::vector<bsp::Entity> ents(2);
    ents[0].pairs = {{"classname", "worldspawn"}};
    ents[1].pairs = {{"classname", "light"}, {"origin", "64 64 100"}, {"light", "300"}};
    b.entities = bsp::unparseEntities(ents);
    return b;
}

std::filesystem::path writeRoom(const std::filesystem::path& dir, const bsp::Bsp& b) {
    std::filesystem::create_directories(dir / "maps");
    std::filesystem::path path = dir / "maps" / "room.bsp";
    writeFileAtomic(path, bsp::serializeBsp(b));
    return path;
}

int runStage(const std::filesystem::path& bspPath, int threads, LightOptions options = {}) {
    CommonOptions common;
    common.mapPath = bspPath;
    common.threads = threads;
    common.commandLine = "-light";
    Log log(false);
    return runLightStage(options, common, log);
}

// Texel of surface `s` at lightmap luxel (x, y).
std::array<uint8_t, 3> texel(const bsp::Bsp& b, int s, int x, int y) {
    const bsp::Surface& surface = b.surfaces[static_cast<size_t>(s)];
    const size_t page = static_cast<size_t>(surface.lightmapNum) * 128 * 128 * 3;
    const size_t at = page + (static_cast<size_t>(surface.lightmapY + y) * 128 + surface.lightmapX + x) * 3;
    return {b.lightmaps[at], b.lightmaps[at + 1], b.lightmaps[at + 2]};
}

TEST(LightPipeline, FloorLuxelsMatchInverseSquareAndShadow) {
    const bsp::Bsp room = makeRoom();
    const auto path = writeRoom(test::tempDir(), room);
    ASSERT_EQ(runStage(path, 2), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    ASSERT_EQ(lit.surfaces[0].lightmapNum, 0);
    ASSERT_FALSE(lit.lightmaps.empty());

    // Where the layout puts the floor's luxels.
    SurfaceGeometry g = surfaceGeometry(room, 0);
    std::optional<RawLightmap> raw = layoutSurfaceLightmap(g, SurfaceLightmapParams{}, LayoutOptions{});
    ASSERT_TRUE(raw);
    ASSERT_EQ(lit.surfaces[0].lightmapWidth, raw->width);
    const ColorOptions color;
    int checked = 0, shadowedCount = 0;
    for (int y = 0; y < raw->height; ++y)
        for (int x = 0; x < raw->width; ++x) {
            const Luxel& lx = raw->luxel(x, y);
            if (!lx.mapped) continue;
            const Vec3 p = lx.origin;
            const Vec3 toLight = Vec3{64, 64, 100} - p;
            const float d = length(toLight);
            // Shadow of the table (z = 50, x and y in 48..80) on the way to the light.
            const float t = (50.0f - p.z) / (100.0f - p.z);
            const Vec3 q = p + toLight * t;
            const bool shadowed = q.x >= 48 && q.x <= 80 && q.y >= 48 && q.y <= 80;
            const bool nearEdge = std::fabs(q.x - 48) < 2 || std::fabs(q.x - 80) < 2 || std::fabs(q.y - 48) < 2 ||
                                  std::fabs(q.y - 80) < 2;
            if (nearEdge) continue;
            const float add = shadowed ? 0.0f : 2250000.0f / (d * d) * (toLight.z / d);
            if (shadowed) ++shadowedCount;
            const Rgb8 expected = colorToBytes(Vec3::splat(add), 1, color);
            const auto got = texel(lit, 0, x, y);
            EXPECT_EQ(got[0], expected[0]) << "luxel " << x << "," << y;
            EXPECT_EQ(got[1], expected[1]);
            ++checked;
        }
    EXPECT_GT(checked, 40);
    EXPECT_GT(shadowedCount, 0);
}

TEST(LightPipeline, CompensateDividesBeforeTheClamp) {
    // q3map2 2.5.17n divides by -compensate before the hue-keeping clamp: light under 255 x
    // compensate keeps its gradations and a light five times too bright still reaches 255 (its
    // -compensate 2 lightmaps of oacmpdm5 peak at 255, not 127).
    auto light = [](const char* intensity, float compensate) {
        bsp::Bsp room = makeRoom();
        std::vector<bsp::Entity> ents = bsp::parseEntities(room.entities, "room");
        ents[1].set("light", intensity);
        room.entities = bsp::unparseEntities(ents);
        const auto path = writeRoom(test::tempDir(), room);
        LightOptions options;
        options.compensate = compensate;
        EXPECT_EQ(runStage(path, 1, options), 0);
        return bsp::readBsp(path);
    };
    auto floorBytes = [](const bsp::Bsp& lit) {
        std::vector<uint8_t> bytes;
        for (int y = 0; y < lit.surfaces[0].lightmapHeight; ++y)
            for (int x = 0; x < lit.surfaces[0].lightmapWidth; ++x)
                for (uint8_t c : texel(lit, 0, x, y)) bytes.push_back(c);
        return bytes;
    };
    const std::vector<uint8_t> saturated = floorBytes(light("5000", 2.0f));
    ASSERT_FALSE(saturated.empty());
    EXPECT_EQ(*std::max_element(saturated.begin(), saturated.end()), 255);
    const std::vector<uint8_t> plain = floorBytes(light("300", 1.0f));
    const std::vector<uint8_t> halved = floorBytes(light("300", 2.0f));
    ASSERT_EQ(plain.size(), halved.size());
    int compared = 0;
    for (size_t i = 0; i < plain.size(); ++i) {
        if (plain[i] < 8 || plain[i] > 250) continue;
        EXPECT_NEAR(halved[i], plain[i] / 2.0, 1.0) << "byte " << i;
        ++compared;
    }
    EXPECT_GT(compared, 0);
}

TEST(LightPipeline, GridPointMatchesEncoding) {
    const auto path = writeRoom(test::tempDir(), makeRoom());
    ASSERT_EQ(runStage(path, 1), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    const GridLayout layout = computeGridLayout(kDefaultGridSize, lit);
    ASSERT_EQ(static_cast<int>(lit.lightGrid.size()), layout.numPoints());
    // Point (64, 64, 128): 28 units above the light, nothing in between.
    int index = -1;
    for (int i = 0; i < layout.numPoints(); ++i)
        if (layout.pointOrigin(i) == Vec3{64, 64, 128}) index = i;
    ASSERT_GE(index, 0);
    LightContribution c{Vec3::splat(2250000.0f / (28.0f * 28.0f)), {0, 0, -1}, 0};
    GridOptions options;
    const bsp::GridPoint expected = encodeGridPoint(accumulateGridSample({&c, 1}, {}, options), options, ColorOptions{});
    const bsp::GridPoint& got = lit.lightGrid[static_cast<size_t>(index)];
    EXPECT_EQ(std::memcmp(&got, &expected, sizeof got), 0);
}

TEST(LightPipeline, WorldspawnRecordsCommandLineAndVersion) {
    const auto path = writeRoom(test::tempDir(), makeRoom());
    ASSERT_EQ(runStage(path, 1), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    auto ents = bsp::parseEntities(lit.entities, "room.bsp");
    ASSERT_FALSE(ents.empty());
    EXPECT_EQ(ents[0].value("_q3map2_cmdline"), "-light");  // q3map2 records the stage and its options
    EXPECT_FALSE(ents[0].value("_q3map2_version").empty());
    // A second run appends to what earlier stages recorded, as "-bsp -meta; -vis; -light" reads.
    ASSERT_EQ(runStage(path, 1), 0);
    ents = bsp::parseEntities(bsp::readBsp(path).entities, "room.bsp");
    EXPECT_EQ(ents[0].value("_q3map2_cmdline"), "-light; -light");
}

TEST(LightPipeline, ThreadCountDoesNotChangeOutput) {
    const bsp::Bsp room = makeRoom();
    const std::filesystem::path dir = test::tempDir();
    const auto one = writeRoom(dir / "one", room);
    const auto two = writeRoom(dir / "two", room);
    LightOptions options;
    options.superSample = 2;
    options.lightSamples = 3;
    ASSERT_EQ(runStage(one, 1, options), 0);
    ASSERT_EQ(runStage(two, 2, options), 0);
    EXPECT_EQ(readFileBytes(one), readFileBytes(two));
}

TEST(LightPipeline, ExternalNoGridAndNoTrace) {
    const std::filesystem::path dir = test::tempDir();
    const auto path = writeRoom(dir, makeRoom());
    LightOptions options;
    options.externalLightmaps = true;
    options.noGrid = true;
    options.noTrace = true;
    ASSERT_EQ(runStage(path, 2, options), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    EXPECT_TRUE(lit.lightmaps.empty());
    EXPECT_TRUE(lit.lightGrid.empty());
    EXPECT_TRUE(std::filesystem::exists(dir / "maps" / "room" / "lm_0000.tga"));
    EXPECT_GE(lit.surfaces[0].lightmapNum, 0);
}

TEST(LightPipeline, NoTraceLightsTheShadow) {
    const std::filesystem::path dir = test::tempDir();
    const auto traced = writeRoom(dir / "a", makeRoom());
    const auto untraced = writeRoom(dir / "b", makeRoom());
    LightOptions options;
    ASSERT_EQ(runStage(traced, 1, options), 0);
    options.noTrace = true;
    ASSERT_EQ(runStage(untraced, 1, options), 0);
    const bsp::Bsp a = bsp::readBsp(traced), b = bsp::readBsp(untraced);
    // The floor luxel right under the light is in the table's shadow only when tracing.
    const int x = a.surfaces[0].lightmapWidth / 2, y = a.surfaces[0].lightmapHeight / 2;
    EXPECT_EQ(texel(a, 0, x, y)[0], 0);
    EXPECT_GT(texel(b, 0, x, y)[0], 200);
}

// The table as brush model *1 of a func_static: it casts a shadow only with _castShadows.
bsp::Bsp makeRoomWithModelTable(const char* castShadows) {
    bsp::Bsp b = makeRoom();
    b.models[0].numSurfaces = 1;
    bsp::Model table{};
    table.mins[0] = table.mins[1] = 48;
    table.maxs[0] = table.maxs[1] = 80;
    table.mins[2] = table.maxs[2] = 50;
    table.firstSurface = 1;
    table.numSurfaces = 1;
    b.models.push_back(table);
    std::vector<bsp::Entity> ents = bsp::parseEntities(b.entities, "room.bsp");
    bsp::Entity e;
    e.pairs = {{"classname", "func_static"}, {"model", "*1"}};
    if (castShadows) e.pairs.emplace_back("_castShadows", castShadows);
    ents.push_back(e);
    b.entities = bsp::unparseEntities(ents);
    return b;
}

TEST(LightPipeline, BrushModelsCastShadowsOnlyWhenAsked) {
    const std::filesystem::path dir = test::tempDir();
    const auto quiet = writeRoom(dir / "a", makeRoomWithModelTable(nullptr));
    const auto casting = writeRoom(dir / "b", makeRoomWithModelTable("1"));
    ASSERT_EQ(runStage(quiet, 1), 0);
    ASSERT_EQ(runStage(casting, 1), 0);
    const bsp::Bsp a = bsp::readBsp(quiet), b = bsp::readBsp(casting);
    const int x = a.surfaces[0].lightmapWidth / 2, y = a.surfaces[0].lightmapHeight / 2;
    EXPECT_GT(texel(a, 0, x, y)[0], 200);
    EXPECT_EQ(texel(b, 0, x, y)[0], 0);
}

TEST(LightPipeline, ShadowedVertexSearchesForALitPosition) {
    // A vertex-lit soup on the floor at (34, 64): the table's shadow (x 32..96 on the floor) covers
    // the vertex itself, so q3map2's search moves it over the 4-unit lattice (x, then y, then z
    // outermost first) and keeps the first lit position. Rays from z + 8 pass 0.3 units beside the
    // table's edge, within 1 % of its 32-unit triangles, and are stopped; so are those of x + 4;
    // x - 4 on the floor is the first one lit.
    bsp::Bsp room = makeRoom();
    q3::test::addQuad(room, {34, 64, 0}, {0, 4, 0}, {4, 0, 0}, 0);
    room.surfaces.back().surfaceType = bsp::MST_TRIANGLE_SOUP;
    room.models[0].numSurfaces = static_cast<int32_t>(room.surfaces.size());
    const auto path = writeRoom(test::tempDir(), room);
    ASSERT_EQ(runStage(path, 1), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    const bsp::DrawVert& v = lit.drawVerts[static_cast<size_t>(lit.surfaces.back().firstVert)];
    ASSERT_EQ(Vec3::fromArray(v.xyz), (Vec3{34, 64, 0}));
    const Vec3 toLight = Vec3{64, 64, 100} - Vec3{30, 64, 0};
    const float d = length(toLight);
    const Rgb8 expected = colorToBytes(Vec3::splat(2250000.0f / (d * d) * (toLight.z / d)), 1, ColorOptions{});
    EXPECT_EQ(v.color[0], expected[0]);
    EXPECT_EQ(v.color[1], expected[1]);
    EXPECT_GT(v.color[0], 0);
}

// A vertex-lit soup lying on the floor: a grid of `columns` x `rows` vertexes from `corner`, `step`
// apart, facing up.
void addSoupGrid(bsp::Bsp& b, Vec3 corner, float step, int columns, int rows) {
    bsp::Surface s{};
    s.shaderNum = 0;
    s.fogNum = -1;
    s.surfaceType = bsp::MST_TRIANGLE_SOUP;
    s.firstVert = static_cast<int32_t>(b.drawVerts.size());
    s.numVerts = columns * rows;
    s.firstIndex = static_cast<int32_t>(b.drawIndexes.size());
    s.lightmapNum = -1;
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < columns; ++x) {
            bsp::DrawVert v{};
            (corner + Vec3{float(x) * step, float(y) * step, 0}).toArray(v.xyz);
            Vec3{0, 0, 1}.toArray(v.normal);
            b.drawVerts.push_back(v);
        }
    for (int y = 0; y + 1 < rows; ++y)
        for (int x = 0; x + 1 < columns; ++x) {
            const int32_t a = y * columns + x, c = a + columns;
            for (int32_t idx : {a, c + 1, a + 1, a, c, c + 1}) b.drawIndexes.push_back(idx);
        }
    s.numIndexes = static_cast<int32_t>(b.drawIndexes.size()) - s.firstIndex;
    b.surfaces.push_back(s);
    b.models[0].numSurfaces = static_cast<int32_t>(b.surfaces.size());
}

TEST(LightPipeline, EveryVertexOfALargeSoupTakesItsOwnLight) {
    // 50 vertexes beside the table's shadow, traced in blocks of several vertexes at once: each one
    // still takes the inverse-square light at its own position, and a second light under the
    // one-sided floor adds nothing to any of them. The thread count changes nothing.
    bsp::Bsp room = makeRoom();
    addSoupGrid(room, {100, 4, 0}, 6, 5, 10);
    std::vector<bsp::Entity> ents = bsp::parseEntities(room.entities, "room");
    ents.push_back({});
    ents.back().pairs = {{"classname", "light"}, {"origin", "110 60 -40"}, {"light", "300"}};
    room.entities = bsp::unparseEntities(ents);
    const std::filesystem::path dir = test::tempDir();
    const auto one = writeRoom(dir / "one", room);
    const auto two = writeRoom(dir / "two", room);
    ASSERT_EQ(runStage(one, 1), 0);
    ASSERT_EQ(runStage(two, 2), 0);
    EXPECT_EQ(readFileBytes(one), readFileBytes(two));
    const bsp::Bsp lit = bsp::readBsp(one);
    const bsp::Surface& soup = lit.surfaces.back();
    ASSERT_EQ(soup.numVerts, 50);
    for (int i = 0; i < soup.numVerts; ++i) {
        const bsp::DrawVert& v = lit.drawVerts[static_cast<size_t>(soup.firstVert + i)];
        const Vec3 toLight = Vec3{64, 64, 100} - Vec3::fromArray(v.xyz);
        const float d = length(toLight);
        const Rgb8 expected = colorToBytes(Vec3::splat(2250000.0f / (d * d) * (toLight.z / d)), 1, ColorOptions{});
        EXPECT_EQ(v.color[0], expected[0]) << "vertex " << i;
        EXPECT_EQ(v.color[2], expected[2]) << "vertex " << i;
    }
}

TEST(LightPipeline, LuxelsNextToAPlanarSurfaceAreLitWhereTheyLie) {
    // A 100 x 100 floor maps luxels 0..6 (s 0.5..6.75); q3map2 also maps the ring of luxels around
    // them (column 7) at their own grid point, one unit up, instead of copying their neighbours.
    bsp::Bsp b = makeRoom();
    b.surfaces.clear();
    b.drawVerts.clear();
    b.drawIndexes.clear();
    q3::test::addQuad(b, {0, 0, 0}, {0, 100, 0}, {100, 0, 0}, 0);
    b.models[0].numSurfaces = 1;
    const auto path = writeRoom(test::tempDir(), b);
    ASSERT_EQ(runStage(path, 1), 0);
    const bsp::Bsp lit = bsp::readBsp(path);
    ASSERT_EQ(lit.surfaces[0].lightmapWidth, 8);
    const Vec3 toLight = Vec3{64, 64, 100} - Vec3{112, 48, 1};
    const float d = length(toLight);
    const Rgb8 expected = colorToBytes(Vec3::splat(2250000.0f / (d * d) * (toLight.z / d)), 1, ColorOptions{});
    const auto got = texel(lit, 0, 7, 3);
    EXPECT_EQ(got[0], expected[0]);
    EXPECT_EQ(got[1], expected[1]);
}

TEST(LightPipeline, MissingBspIsAnError) {
    EXPECT_ANY_THROW(runStage(test::tempDir() / "maps" / "nothing.bsp", 1));
}

// A later pass over a raw lightmap (a radiosity bounce) lights the sample points the first pass
// placed: handed the first pass's result, it lays nothing out again and gives the luxels a pass of
// its own would give.
TEST(PassSamples, ALaterPassLightsTheFirstPassesPoints) {
    CommonOptions common;
    common.mapPath = writeRoom(test::tempDir(), makeRoom());
    common.threads = 1;
    Log log(false);
    LightContext ctx;
    loadLightInputs(ctx, common, log);
    buildSurfaceGeometry(ctx);
    buildScene(ctx);
    createLights(ctx, log);
    ASSERT_FALSE(ctx.lights.empty());
    const LayoutOptions layout = layoutOptionsFor(ctx, log);
    const LightingEnv env = surfaceLightingEnv(ctx);
    const int floor[] = {0};

    SurfacePass first{ctx.lights, true, false};
    first.keepSamples = true;
    const SurfaceLight direct = lightSurface(ctx, env, floor, layout, nullptr, first);
    ASSERT_TRUE(direct.ok);
    ASSERT_TRUE(direct.samples);
    EXPECT_EQ(direct.samples->points.size(), direct.samples->states.size());

    // A bounce-like pass (no ambient) on its own, and one handed the first pass's samples.
    const SurfacePass later{ctx.lights, false, false};
    const SurfaceLight alone = lightSurface(ctx, env, floor, layout, nullptr, later);
    const SurfaceLight reused = lightSurface(ctx, env, floor, layout, nullptr, later, &direct);
    ASSERT_TRUE(alone.ok && reused.ok);
    EXPECT_FALSE(alone.samples);  // kept only when asked
    // The layout's luxels go with the samples: kept for a later pass, freed (not just emptied) when
    // none follows, so that the next lightmap reuses their memory.
    EXPECT_FALSE(direct.layout.luxels.empty());
    EXPECT_EQ(alone.layout.luxels.capacity(), 0u);
    EXPECT_EQ(alone.layout.triangles.capacity(), 0u);
    EXPECT_FALSE(alone.layout.surfaceCoords.empty());  // what the store still reads
    EXPECT_EQ(reused.luxelCount, alone.luxelCount);
    ASSERT_EQ(reused.layers.size(), alone.layers.size());
    for (size_t k = 0; k < alone.layers.size(); ++k) EXPECT_EQ(reused.layers[k].color, alone.layers[k].color);
    EXPECT_EQ(reused.used, alone.used);
    // The floor is lit where the table does not shade it, so the comparison above is not of darkness.
    float brightest = 0;
    for (const Vec3& c : alone.layers[0].color) brightest = std::max(brightest, c.x);
    EXPECT_GT(brightest, 10.0f);

    // The samples handed over are the ones lit: points moved off the floor light differently.
    SurfaceLight moved = direct;
    auto shifted = std::make_shared<LuxelSamples>(*direct.samples);
    for (std::optional<SamplePoint>& p : shifted->points)
        if (p) p->origin.z += 20;
    moved.samples = shifted;
    const SurfaceLight fromMoved = lightSurface(ctx, env, floor, layout, nullptr, later, &moved);
    ASSERT_TRUE(fromMoved.ok);
    EXPECT_NE(fromMoved.layers[0].color, alone.layers[0].color);
}

}  // namespace
}  // namespace q3::light
