// Phong shading seen from outside: the -shade / -shadeangle options, and the light stage lighting
// the vertices of a smoothed edge with the averaged normal while writing the stored normals back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "bsp_scene.h"
#include "color_pipeline.h"
#include "command_line.h"
#include "common_option_table.h"
#include "option_parser.h"
#include "file_io.h"
#include "shader_info.h"
#include "light_options.h"
#include "light_stage.h"
#include "test_data.h"

namespace q3::light {
namespace {

LightOptions parse(const std::vector<std::string>& args) {
    std::vector<cli::StageDescription> stages = cli::q3map2Stages();
    for (cli::StageDescription& s : stages)
        if (s.name == "-light") {
            s.available = true;
            s.options = cli::describe(lightOptionTable());
        }
    LightOptions options;
    cli::parseOptions(lightOptionTable(), args, cli::stageParseContext("-light", cli::commonOptionTable(), stages),
                      options);
    return options;
}

std::string errorOf(const std::vector<std::string>& args) {
    try {
        parse(args);
    } catch (const cli::UsageError& e) {
        return e.what();
    }
    return "<no error>";
}

TEST(PhongOptions, ShadeAndShadeAngleParse) {
    EXPECT_FALSE(parse({}).shade);
    const LightOptions bare = parse({"-shade"});
    EXPECT_TRUE(bare.shade);
    EXPECT_EQ(bare.shadeAngle, 0.0f);
    const LightOptions angle = parse({"-shadeangle", "60"});
    EXPECT_TRUE(angle.shade);
    EXPECT_EQ(angle.shadeAngle, 60.0f);
    // As q3map2: an angle of 0 sets no default and does not switch phong shading on by itself.
    EXPECT_FALSE(parse({"-shadeangle", "0"}).shade);
    EXPECT_TRUE(parse({"-shade", "-shadeangle", "0"}).shade);
}

TEST(PhongOptions, BadAnglesAreRefused) {
    EXPECT_EQ(errorOf({"-shadeangle", "-1"}), "-shadeangle: -1 is out of range (must be between 0 and 360)");
    EXPECT_EQ(errorOf({"-shadeangle", "abc"}), "-shadeangle: 'abc' is not a number (-shadeangle <A>)");
    EXPECT_EQ(errorOf({"-shadeangle"}), "-shadeangle needs 1 value (-shadeangle <A>)");
}

// A floor (normal +z) and a wall (normal +x) meeting along x = 0, z = 0, both vertex lit (their
// shader is surfaceparm pointlight, as the BSP's surface flags say), and a point light in front of
// the corner.
constexpr float kLightValue = 20;
const Vec3 kLightOrigin{40, 8, 10};

bsp::Bsp makeCorner() {
    bsp::Bsp b;
    b.version = bsp::kVersionQ3;
    b.headerLumps = 18;
    bsp::Shader sh{};
    std::strcpy(sh.name, "textures/phong/corner");
    sh.contentFlags = 1;
    sh.surfaceFlags = int32_t(q3::surfaceflags::PointLight);
    b.shaders.push_back(sh);
    q3::test::addQuad(b, {0, 0, 0}, {0, 64, 0}, {64, 0, 0}, 0);  // floor: verts 0..3, vertex 0 at the origin
    q3::test::addQuad(b, {0, 0, 0}, {0, 0, 64}, {0, 64, 0}, 0);  // wall: verts 4..7, vertex 4 at the origin
    for (bsp::Surface& s : b.surfaces) s.lightmapNum = -3;
    bsp::Model world{};
    world.maxs[0] = world.maxs[1] = world.maxs[2] = 64;
    world.numSurfaces = 2;
    b.models.push_back(world);
    std::vector<bsp::Entity> ents(2);
    ents[0].pairs = {{"classname", "worldspawn"}};
    ents[1].pairs = {{"classname", "light"}, {"origin", "40 8 10"}, {"light", "20"}};
    b.entities = bsp::unparseEntities(ents);
    return b;
}

// The vertex colour of a point light at a vertex lit with `normal` (sampled at the vertex itself,
// as q3map2's IlluminateVertexes does): photons / d^2 * cos, through the default colour pipeline.
uint8_t expectedByte(Vec3 xyz, Vec3 normal) {
    const Vec3 p = xyz;
    const Vec3 toLight = kLightOrigin - p;
    const float d = length(toLight);
    const float add = kLightValue * 7500.0f / (d * d) * (dot(normal, toLight) / d);
    return colorToBytes(Vec3::splat(add), 1, ColorOptions{})[0];
}

bsp::Bsp lightCorner(const std::string& name, LightOptions options) {
    const std::filesystem::path dir = test::tempDir() / name;
    std::filesystem::create_directories(dir / "maps");
    const std::filesystem::path path = dir / "maps" / "corner.bsp";
    writeFileAtomic(path, bsp::serializeBsp(makeCorner()));
    CommonOptions common;
    common.mapPath = path;
    common.threads = 2;
    common.commandLine = "-light corner.bsp";
    Log log(false);
    EXPECT_EQ(runLightStage(options, common, log), 0);
    return bsp::readBsp(path);
}

TEST(PhongStage, SmoothedCornerVertexGetsLightBetweenItsFaces) {
    const bsp::Bsp flat = lightCorner("flat", LightOptions{});
    LightOptions shaded;
    shaded.shade = true;
    shaded.shadeAngle = 100;
    const bsp::Bsp smooth = lightCorner("smooth", shaded);

    const Vec3 origin{0, 0, 0};
    const uint8_t floorByte = expectedByte(origin, {0, 0, 1});
    const uint8_t wallByte = expectedByte(origin, {1, 0, 0});
    const uint8_t smoothByte = expectedByte(origin, normalize(Vec3{1, 0, 1}));
    ASSERT_LT(floorByte + 10, smoothByte);  // the scene really separates the three cases
    ASSERT_LT(smoothByte + 2, wallByte);

    EXPECT_EQ(flat.drawVerts[0].color[0], floorByte);
    EXPECT_EQ(flat.drawVerts[4].color[0], wallByte);
    EXPECT_EQ(smooth.drawVerts[0].color[0], smoothByte);
    EXPECT_EQ(smooth.drawVerts[4].color[0], smoothByte);
    // Vertices away from the edge keep their own normal and light.
    EXPECT_EQ(smooth.drawVerts[2].color[0], flat.drawVerts[2].color[0]);
    EXPECT_EQ(smooth.drawVerts[5].color[0], flat.drawVerts[5].color[0]);

    // The written BSP keeps the stored normals.
    for (size_t v = 0; v < smooth.drawVerts.size(); ++v)
        EXPECT_EQ(std::memcmp(smooth.drawVerts[v].normal, flat.drawVerts[v].normal, sizeof(float) * 3), 0) << v;

    // A breaking angle below the corner's 90 degrees leaves it as it was.
    shaded.shadeAngle = 80;
    const bsp::Bsp sharp = lightCorner("sharp", shaded);
    EXPECT_EQ(sharp.drawVerts[0].color[0], floorByte);
    EXPECT_EQ(sharp.drawVerts[4].color[0], wallByte);
}

}  // namespace
}  // namespace q3::light
