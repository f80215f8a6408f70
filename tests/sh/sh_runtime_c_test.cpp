// The C interface: same results as the C++ runtime, failures as NULL plus one line, null-safe.
#include <gtest/gtest.h>

#include <cstring>

#include "sh.h"
#include "sh_grid_runtime.h"
#include "sh_grid_runtime_c.h"
#include "sh_test_support.h"

extern "C" int q3sh_test_c_sample(const unsigned char* bsp, size_t size, const float position[3],
                                  const float normal[3], float rgb[3], char* error, size_t errorSize);

namespace q3::sh {
namespace {

GridSH twoPointGrid() {
    GridSH grid;
    grid.size[0] = grid.size[1] = grid.size[2] = 16;
    grid.bounds[0] = 2;
    grid.bounds[1] = grid.bounds[2] = 1;
    grid.points.push_back(toGridPoint(projectAmbient({1, 0.5, 0.25})));
    grid.points.push_back(toGridPoint(projectDirectionalIrradiance({0, 0, 1}, {2, 2, 2})));
    return grid;
}

std::vector<uint8_t> bspWithGrid(const GridSH& grid) {
    std::vector<std::vector<uint8_t>> lumps(19);
    lumps[18] = encodeGridLump(grid);
    return test::buildBsp(47, 19, lumps);
}

TEST(ShRuntimeC, MatchesTheCppRuntime) {
    const std::vector<uint8_t> bsp = bspWithGrid(twoPointGrid());
    char error[128] = "unset";
    q3sh_grid* grid = q3sh_grid_load(bsp.data(), bsp.size(), error, sizeof error);
    ASSERT_NE(grid, nullptr) << error;
    EXPECT_STREQ(error, "");
    EXPECT_EQ(q3sh_grid_source(grid), Q3SH_SOURCE_LUMP18);
    float mins[3], cell[3];
    int bounds[3];
    q3sh_grid_info(grid, mins, cell, bounds);
    EXPECT_EQ(bounds[0], 2);
    EXPECT_EQ(cell[1], 16);

    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.data(), bsp.size()), "");
    const float pos[3] = {4, 3, -2};
    float coeffs[27];
    q3sh_grid_sample(grid, pos, coeffs);
    const GridPointSH p = rt.sample(pos);
    EXPECT_EQ(std::memcmp(coeffs, p.coeffs, sizeof coeffs), 0);

    const float up[3] = {0, 0, 1};
    float rgb[3], expected[3];
    q3sh_eval_irradiance(coeffs, up, rgb);
    irradianceAt(p, up, expected);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb[c], expected[c]);
    // A quarter of the way from the ambient point to the light point.
    EXPECT_NEAR(rgb[0], 0.75 * 1 + 0.25 * 2 * 1.0625, 1e-5);

    float faces[18];
    q3sh_ambient_cube(coeffs, faces);
    const AmbientCube cube = toAmbientCube(p);
    EXPECT_EQ(std::memcmp(faces, cube.face, sizeof faces), 0);

    float dir[3], directed[3], ambient[3];
    q3sh_legacy_lighting(coeffs, dir, directed, ambient);
    const LegacyLighting light = toLegacyLighting(p);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(dir[c], light.direction[c]);
        EXPECT_EQ(directed[c], light.directed[c]);
        EXPECT_EQ(ambient[c], light.ambient[c]);
    }
    q3sh_grid_free(grid);
}

TEST(ShRuntimeC, CallableFromC) {
    const std::vector<uint8_t> bsp = bspWithGrid(twoPointGrid());
    const float pos[3] = {16, 0, 0}, up[3] = {0, 0, 1};
    float rgb[3];
    char error[64];
    EXPECT_EQ(q3sh_test_c_sample(bsp.data(), bsp.size(), pos, up, rgb, error, sizeof error), Q3SH_SOURCE_LUMP18);
    EXPECT_NEAR(rgb[1], 2 * 1.0625, 1e-5);
}

TEST(ShRuntimeC, FailureGivesNullAndOneLine) {
    std::vector<uint8_t> bsp = bspWithGrid(twoPointGrid());
    bsp.pop_back();  // lump 18 now one byte short of its header's claim... and of its directory entry
    test::putU32(bsp, 8 + 8 * 18 + 4, uint32_t(40 + 108 * 2 - 1));
    char error[200];
    EXPECT_EQ(q3sh_grid_load(bsp.data(), bsp.size(), error, sizeof error), nullptr);
    EXPECT_NE(std::strstr(error, "SH grid lump: length"), nullptr) << error;
    EXPECT_EQ(std::strchr(error, '\n'), nullptr);
    // A tiny buffer gets a truncated, still terminated message; a null one is fine too.
    char tiny[8];
    EXPECT_EQ(q3sh_grid_load(bsp.data(), bsp.size(), tiny, sizeof tiny), nullptr);
    EXPECT_EQ(std::strlen(tiny), 7u);
    EXPECT_EQ(q3sh_grid_load(bsp.data(), bsp.size(), nullptr, 0), nullptr);
    EXPECT_EQ(q3sh_grid_load(nullptr, 0, error, sizeof error), nullptr);
}

TEST(ShRuntimeC, NullArgumentsAreHarmless) {
    float coeffs[27], rgb[3] = {9, 9, 9}, faces[18];
    const float pos[3] = {0, 0, 0};
    q3sh_grid_sample(nullptr, pos, coeffs);
    for (float c : coeffs) EXPECT_EQ(c, 0.0f);
    q3sh_eval_irradiance(nullptr, pos, rgb);
    EXPECT_EQ(rgb[0], 0.0f);
    q3sh_ambient_cube(nullptr, faces);
    q3sh_legacy_lighting(nullptr, nullptr, nullptr, nullptr);
    q3sh_grid_info(nullptr, nullptr, nullptr, nullptr);
    EXPECT_EQ(q3sh_grid_source(nullptr), Q3SH_SOURCE_NONE);
    q3sh_grid_free(nullptr);
}

}  // namespace
}  // namespace q3::sh
