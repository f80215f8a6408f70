#include <gtest/gtest.h>

#include <fstream>

#include "file_io.h"
#include "script.h"
#include "srf_file.h"
#include "test_data.h"

namespace q3::light {
namespace {

constexpr const char* kSample = R"(default
{
	castShadows 1
	receiveShadows 1
	sampleSize 8
	ambientColor ( 0.000000 0.000000 0.000000 )
	longestCurve 0.000000
}

0 // PLANAR V: 4 I: 6 planar
{
	shader textures/base_wall/concrete
}

3 // PATCH V: 81 I: 384
{
	shader textures/gothic_trim/pitted_rust
	parent 1
	entity 5
	castShadows 0
	receiveShadows 2
	sampleSize 32
	ambientColor ( 0.5 0.25 1 )
	longestCurve 182.5
	lightmapAxis ( 0.000000 0.000000 1.000000 )
	someFutureKey 1 2 3
}
)";

TEST(SrfFile, ParsesEveryField) {
    const SurfaceExtras e = parseSurfaceExtras(kSample, "maps/test.srf");
    EXPECT_TRUE(e.loaded);
    EXPECT_EQ(e.defaults.sampleSize, 8);
    EXPECT_EQ(e.defaults.castShadows, 1);
    EXPECT_EQ(e.surfaces.size(), 4u);

    const SurfaceExtra& s0 = e.forSurface(0);
    EXPECT_EQ(s0.shader, "textures/base_wall/concrete");
    EXPECT_EQ(s0.sampleSize, 8);  // inherited from the default block
    EXPECT_EQ(s0.parent, -1);

    const SurfaceExtra& s3 = e.forSurface(3);
    EXPECT_EQ(s3.shader, "textures/gothic_trim/pitted_rust");
    EXPECT_EQ(s3.parent, 1);
    EXPECT_EQ(s3.entity, 5);
    EXPECT_EQ(s3.castShadows, 0);
    EXPECT_EQ(s3.receiveShadows, 2);
    EXPECT_EQ(s3.sampleSize, 32);
    EXPECT_EQ(s3.ambientColor, (Vec3{0.5f, 0.25f, 1.0f}));
    EXPECT_FLOAT_EQ(s3.longestCurve, 182.5f);
    EXPECT_EQ(s3.lightmapAxis, (Vec3{0, 0, 1}));

    // Surfaces without a block (1, 2, and beyond the file) get the defaults.
    EXPECT_EQ(e.forSurface(1).sampleSize, 8);
    EXPECT_TRUE(e.forSurface(2).shader.empty());
    EXPECT_EQ(e.forSurface(99).sampleSize, 8);
    EXPECT_EQ(e.forSurface(-1).castShadows, 1);
}

TEST(SrfFile, DefaultSampleSizeIsOverriddenByTheFile) {
    EXPECT_EQ(parseSurfaceExtras("default\n{\n}\n", "a.srf", 4).defaults.sampleSize, 4);
    EXPECT_EQ(parseSurfaceExtras("default\n{\nsampleSize 64\n}\n", "a.srf", 4).defaults.sampleSize, 64);
}

std::string errorOf(const std::string& text) {
    try {
        parseSurfaceExtras(text, "maps/bad.srf");
    } catch (const ScriptError& e) {
        return e.what();
    }
    return "";
}

TEST(SrfFile, ErrorsNameFileAndLine) {
    EXPECT_EQ(errorOf("default\n{\n}\n-2\n{\n}\n"), "maps/bad.srf:4: bogus surface number -2");
    EXPECT_EQ(errorOf("default\nsampleSize 3\n"), "maps/bad.srf:2: { not found");
    EXPECT_EQ(errorOf("7\n{\n sampleSize\n}\n"), "maps/bad.srf:3: missing value for sampleSize");
    EXPECT_EQ(errorOf("7\n{\n sampleSize big\n}\n"), "maps/bad.srf:3: expected a number for sampleSize, found 'big'");
    EXPECT_EQ(errorOf("7\n{\n lightmapAxis 0 0 1\n}\n"), "maps/bad.srf:3: expected '(' after lightmapAxis");
    EXPECT_EQ(errorOf("7\n{\n castShadows 1\n"), "maps/bad.srf:3: unexpected end of file, } not found");
    EXPECT_EQ(errorOf("surf\n{\n}\n"), "maps/bad.srf:1: expected a surface number or 'default', found 'surf'");
}

TEST(SrfFile, MissingFileGivesDefaults) {
    const auto dir = test::tempDir();
    const SurfaceExtras e = loadSurfaceExtras(dir / "nothere.srf", 12);
    EXPECT_FALSE(e.loaded);
    EXPECT_EQ(e.forSurface(5).sampleSize, 12);
    EXPECT_EQ(e.forSurface(5).castShadows, 1);

    writeFileAtomic(dir / "here.srf", std::string("default\n{\nsampleSize 20\n}\n2\n{\nentity 3\n}\n"));
    const SurfaceExtras f = loadSurfaceExtras(dir / "here.srf", 12);
    EXPECT_TRUE(f.loaded);
    EXPECT_EQ(f.forSurface(2).entity, 3);
    EXPECT_EQ(f.forSurface(2).sampleSize, 20);
}

}  // namespace
}  // namespace q3::light
