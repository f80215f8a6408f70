// The engine-side runtime: locating the grid in BSP images, trilinear sampling with clamping,
// rejection of malformed data, conversions to ambient cube and legacy lighting.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "sh.h"
#include "sh_bsp_scan.h"
#include "sh_grid_runtime.h"
#include "sh_test_support.h"

namespace q3::sh {
namespace {

// A 3x2x2 grid at (16, -32, 0) with cells 32x64x16; every coefficient distinct.
GridSH probeGrid() {
    GridSH grid;
    const float mins[3] = {16, -32, 0}, size[3] = {32, 64, 16};
    const int32_t bounds[3] = {3, 2, 2};
    for (int a = 0; a < 3; ++a) {
        grid.mins[a] = mins[a];
        grid.size[a] = size[a];
        grid.bounds[a] = bounds[a];
    }
    grid.points.resize(12);
    for (size_t p = 0; p < 12; ++p)
        for (int i = 0; i < 9; ++i)
            for (int c = 0; c < 3; ++c) grid.points[p].coeffs[i][c] = float(p * 7 + i * 3 + c) * 0.125f - 2.0f;
    return grid;
}

float coeffAt(const GridSH& g, int x, int y, int z, int i, int c) {
    return g.points[size_t(x + y * g.bounds[0] + z * g.bounds[0] * g.bounds[1])].coeffs[i][c];
}

std::vector<std::vector<uint8_t>> lumpsWith(int index, std::vector<uint8_t> data, int count) {
    std::vector<std::vector<uint8_t>> lumps(count);
    lumps[0] = {'{', '}', 0};
    lumps[index] = std::move(data);
    return lumps;
}

void expectOneLine(const std::string& error, const char* mentions) {
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_NE(error.find(mentions), std::string::npos) << error;
}

TEST(ShRuntime, FindsLump18OfVersion47) {
    const GridSH grid = probeGrid();
    const std::vector<uint8_t> bsp = test::buildBsp(47, 19, lumpsWith(18, encodeGridLump(grid), 19));
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.data(), bsp.size(), "maps/probe.bsp"), "");
    EXPECT_EQ(rt.source(), GridSource::Lump18);
    EXPECT_EQ(rt.grid().points.size(), 12u);
    EXPECT_EQ(rt.grid().bounds[0], 3);
}

TEST(ShRuntime, FindsTheBspxLumpOfVersion46) {
    const GridSH grid = probeGrid();
    const std::vector<uint8_t> bsp = test::buildBsp(46, 17, lumpsWith(1, std::vector<uint8_t>(72, 1), 17),
                                                    {{"OTHER", {1, 2, 3}}, {"LIGHTGRID_SH", encodeGridLump(grid)}});
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.data(), bsp.size()), "");
    EXPECT_EQ(rt.source(), GridSource::Bspx);
    const float at[3] = {48, 32, 16};
    const GridPointSH p = rt.sample(at);
    EXPECT_EQ(p.coeffs[5][2], coeffAt(grid, 1, 1, 1, 5, 2));
}

TEST(ShRuntime, SampleAtAProbeIsThatProbe) {
    GridRuntime rt;
    rt.setGrid(probeGrid(), GridSource::Lump18);
    const GridSH& g = rt.grid();
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) {
                const float pos[3] = {g.mins[0] + x * g.size[0], g.mins[1] + y * g.size[1], g.mins[2] + z * g.size[2]};
                const GridPointSH p = rt.sample(pos);
                for (int i = 0; i < 9; ++i)
                    for (int c = 0; c < 3; ++c) EXPECT_EQ(p.coeffs[i][c], coeffAt(g, x, y, z, i, c));
            }
}

TEST(ShRuntime, InterpolatesTrilinearly) {
    GridRuntime rt;
    rt.setGrid(probeGrid(), GridSource::Lump18);
    const GridSH& g = rt.grid();
    // Between x = 1..2, y = 0..1, z = 0..1 at fractions (0.25, 0.5, 0.75).
    const float pos[3] = {16 + 32 * 1.25f, -32 + 64 * 0.5f, 16 * 0.75f};
    const GridPointSH p = rt.sample(pos);
    const double tx = 0.25, ty = 0.5, tz = 0.75;
    for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c) {
            double expected = 0;
            for (int corner = 0; corner < 8; ++corner) {
                const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
                const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
                expected += w * coeffAt(g, 1 + dx, dy, dz, i, c);
            }
            EXPECT_NEAR(p.coeffs[i][c], expected, 1e-5) << i << "," << c;
        }
    // One hand-computed value: coefficient v(p,i,c) = (7p + 3i + c)/8 - 2 is linear in the point
    // index p = x + 3y + 6z, so the blend is v at p = 1.25 + 3*0.5 + 6*0.75 = 7.25.
    EXPECT_NEAR(p.coeffs[0][0], (7 * 7.25) / 8 - 2, 1e-5);
    EXPECT_NEAR(p.coeffs[8][2], (7 * 7.25 + 24 + 2) / 8 - 2, 1e-5);
}

TEST(ShRuntime, ClampsOutsideTheGrid) {
    GridRuntime rt;
    rt.setGrid(probeGrid(), GridSource::Lump18);
    const GridSH& g = rt.grid();
    const float far[3] = {1e6f, 1e6f, 1e6f};
    const float below[3] = {-1e6f, -1e6f, -1e6f};
    const float side[3] = {16 + 32 * 0.5f, -1000, 16 * 0.5f};  // y clamped to 0, x and z blended
    const GridPointSH a = rt.sample(far), b = rt.sample(below), c = rt.sample(side);
    EXPECT_EQ(a.coeffs[3][1], coeffAt(g, 2, 1, 1, 3, 1));
    EXPECT_EQ(b.coeffs[3][1], coeffAt(g, 0, 0, 0, 3, 1));
    const double expected = 0.25 * (coeffAt(g, 0, 0, 0, 4, 0) + coeffAt(g, 1, 0, 0, 4, 0) + coeffAt(g, 0, 0, 1, 4, 0) +
                                     coeffAt(g, 1, 0, 1, 4, 0));
    EXPECT_NEAR(c.coeffs[4][0], expected, 1e-5);
    const float nan[3] = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
    const GridPointSH d = rt.sample(nan);  // treated as the grid origin along that axis, no crash
    EXPECT_TRUE(std::isfinite(d.coeffs[0][0]));
}

TEST(ShRuntime, SinglePointGridAndEmptyRuntime) {
    GridSH one;
    one.size[0] = one.size[1] = one.size[2] = 8;
    one.bounds[0] = one.bounds[1] = one.bounds[2] = 1;
    one.points.resize(1);
    one.points[0].coeffs[0][0] = 3.5f;
    GridRuntime rt;
    const float pos[3] = {100, -5, 7};
    EXPECT_EQ(rt.sample(pos).coeffs[0][0], 0.0f);
    rt.setGrid(one, GridSource::Lump18);
    EXPECT_EQ(rt.sample(pos).coeffs[0][0], 3.5f);
}

TEST(ShRuntime, RejectsMalformedShLumps) {
    const std::vector<uint8_t> good = encodeGridLump(probeGrid());
    GridRuntime rt;
    std::vector<uint8_t> shortLump(good.begin(), good.end() - 4);
    std::vector<uint8_t> bsp = test::buildBsp(47, 19, lumpsWith(18, shortLump, 19));
    expectOneLine(rt.loadFromBsp(bsp.data(), bsp.size(), "maps/bad.bsp"), "maps/bad.bsp: lump 18 SH grid lump: length");
    EXPECT_EQ(rt.source(), GridSource::None);

    std::vector<uint8_t> mismatch = good;
    test::putU32(mismatch, 36, 11);
    bsp = test::buildBsp(47, 19, lumpsWith(18, mismatch, 19));
    expectOneLine(rt.loadFromBsp(bsp.data(), bsp.size(), "m.bsp"), "numPoints 11 != gridBounds product 12");

    std::vector<uint8_t> nan = good;
    test::putF32(nan, 40 + 5 * 108 + 8, std::numeric_limits<float>::quiet_NaN());
    bsp = test::buildBsp(46, 17, {}, {{"LIGHTGRID_SH", nan}});
    expectOneLine(rt.loadFromBsp(bsp.data(), bsp.size(), "m.bsp"), "BSPX SH grid lump: point 5 coefficient 0 channel 2 is not finite");
}

TEST(ShRuntime, RejectsBspxEntryOutOfRange) {
    std::vector<uint8_t> bsp = test::buildBsp(46, 17, {}, {{"LIGHTGRID_SH", encodeGridLump(probeGrid())}});
    const size_t dirStart = 8 + 8 * 17;
    test::putU32(bsp, dirStart + 8 + 28, uint32_t(bsp.size()));  // length runs past the end
    GridRuntime rt;
    expectOneLine(rt.loadFromBsp(bsp.data(), bsp.size(), "x.bsp"), "BSPX lump LIGHTGRID_SH");
    test::putU32(bsp, dirStart + 4, 0x10000000);  // directory count past the end
    expectOneLine(rt.loadFromBsp(bsp.data(), bsp.size(), "x.bsp"), "BSPX directory");
}

TEST(ShRuntime, RejectsBadHeaders) {
    GridRuntime rt;
    const uint8_t tiny[4] = {'I', 'B', 'S', 'P'};
    expectOneLine(rt.loadFromBsp(tiny, 4, "a.bsp"), "a.bsp: not a BSP");
    std::vector<uint8_t> bsp = test::buildBsp(46, 17, lumpsWith(15, std::vector<uint8_t>(8, 1), 17));
    std::vector<uint8_t> bad = bsp;
    bad[0] = 'V';
    expectOneLine(rt.loadFromBsp(bad.data(), bad.size()), "ident");
    bad = bsp;
    test::putU32(bad, 4, 38);
    expectOneLine(rt.loadFromBsp(bad.data(), bad.size()), "unsupported IBSP version 38");
    bad = bsp;
    test::putU32(bad, 8 + 8 * 15 + 4, 1000);
    expectOneLine(rt.loadFromBsp(bad.data(), bad.size()), "lump 15");
    expectOneLine(rt.loadFromBsp(bsp.data(), 100), "truncated");
}

TEST(ShRuntime, Version47With18LumpsHasNoShLump) {
    // Quake Live layout: the data of lump 0 starts right after 18 entries, inside where a 19th
    // entry would be, so the reader must not take it for lump 18.
    const float mins[3] = {0, 0, 0}, maxs[3] = {64, 64, 128};
    std::vector<std::vector<uint8_t>> lumps(18);
    const std::string ents = "{\n\"classname\" \"worldspawn\"\n}\n";
    lumps[0].assign(ents.begin(), ents.end());
    lumps[7] = test::worldModelLump(mins, maxs);
    lumps[15].assign(8 * 2 * 2 * 2, 0);
    for (size_t p = 0; p < 8; ++p) lumps[15][p * 8] = 10;
    const std::vector<uint8_t> bsp = test::buildBsp(47, 18, lumps);
    BspDirectory dir;
    ASSERT_EQ(readBspDirectory(bsp.data(), bsp.size(), dir), "");
    EXPECT_EQ(dir.lumpCount, 18);
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.data(), bsp.size()), "");
    EXPECT_EQ(rt.source(), GridSource::Legacy);
}

TEST(ShRuntime, Version47With17LumpsIsRead) {
    // id-lineage tools also write version 47 with the plain 17-entry header.
    const float mins[3] = {0, 0, 0}, maxs[3] = {64, 64, 128};
    std::vector<std::vector<uint8_t>> lumps(17);
    const std::string ents = "{ \"classname\" \"worldspawn\" }";
    lumps[0].assign(ents.begin(), ents.end());
    lumps[7] = test::worldModelLump(mins, maxs);
    lumps[15].assign(8 * 8, 7);
    const std::vector<uint8_t> bsp = test::buildBsp(47, 17, lumps);
    BspDirectory dir;
    ASSERT_EQ(readBspDirectory(bsp.data(), bsp.size(), dir), "");
    EXPECT_EQ(dir.lumpCount, 17);
    EXPECT_EQ(dir.lumps[15].size, 64u);
    GridRuntime rt;
    ASSERT_EQ(rt.loadFromBsp(bsp.data(), bsp.size()), "");
    EXPECT_EQ(rt.source(), GridSource::Legacy);
}

TEST(ShRuntime, SurvivesHostileBytes) {
    const std::vector<uint8_t> bsp = test::buildBsp(47, 19, lumpsWith(18, encodeGridLump(probeGrid()), 19),
                                                    {{"LIGHTGRID_SH", encodeGridLump(probeGrid())}});
    GridRuntime rt;
    for (size_t length = 0; length < bsp.size(); length += 7) rt.loadFromBsp(bsp.data(), length);
    std::mt19937 rng(4242);
    std::uniform_int_distribution<size_t> header(0, 200), anywhere(0, bsp.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    int accepted = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::vector<uint8_t> mutated = bsp;
        for (int k = 0; k < 4; ++k) mutated[trial % 2 ? header(rng) : anywhere(rng)] = uint8_t(byte(rng));
        const std::string err = rt.loadFromBsp(mutated.data(), mutated.size());
        if (err.empty()) {
            ++accepted;
            const float pos[3] = {40, 0, 8};
            const GridPointSH p = rt.sample(pos);
            EXPECT_TRUE(std::isfinite(p.coeffs[0][0]));
        } else {
            EXPECT_EQ(err.find('\n'), std::string::npos);
        }
    }
    EXPECT_GT(accepted, 0);
}

TEST(ShRuntime, IrradianceAndAmbientCubeOfOneLight) {
    const SH9Color sh = projectDirectionalIrradiance({1, 0, 0}, {1, 0.5, 0.25});
    const GridPointSH p = toGridPoint(sh);
    const float nx[3] = {1, 0, 0};
    float rgb[3];
    irradianceAt(p, nx, rgb);
    EXPECT_NEAR(rgb[0], 1.0625, 1e-6);
    EXPECT_NEAR(rgb[1], 0.5 * 1.0625, 1e-6);
    const AmbientCube cube = toAmbientCube(p);
    const double expected[6] = {1.0625, 0.0625, 0.09375, 0.09375, 0.09375, 0.09375};  // curve at c = 1, -1, 0
    for (int f = 0; f < 6; ++f) {
        EXPECT_NEAR(cube.face[f][0], expected[f], 1e-6) << f;
        EXPECT_NEAR(cube.face[f][2], 0.25 * expected[f], 1e-6) << f;
    }
}

TEST(ShRuntime, AmbientCubeSeesRedAndBlueApart) {
    SH9Color sh;
    addDirectionalIrradiance(sh, {0, -1, 0}, {1, 0, 0});
    addDirectionalIrradiance(sh, {0, 1, 0}, {0, 0, 1});
    const AmbientCube cube = toAmbientCube(toGridPoint(sh));
    EXPECT_GT(cube.face[3][0], 10 * cube.face[3][2]);  // -Y red
    EXPECT_GT(cube.face[2][2], 10 * cube.face[2][0]);  // +Y blue
}

TEST(ShRuntime, LegacyLightingOfOneLightPlusAmbient) {
    // Least-squares fit of a + d max(0, n.l) to the L2 curve of a unit light: a = 0.003125,
    // d = 0.9875 (see docs/sh-engine-integration.md); ambient adds to a exactly.
    const Vec3d l = normalized({0.3, -0.4, 0.6});
    SH9Color sh = projectDirectionalIrradiance(l, {1, 2, 0.5});
    addAmbient(sh, {0.2, 0.1, 0.0});
    const LegacyLighting light = toLegacyLighting(toGridPoint(sh));
    EXPECT_NEAR(light.direction[0], l.x, 1e-5);
    EXPECT_NEAR(light.direction[1], l.y, 1e-5);
    EXPECT_NEAR(light.direction[2], l.z, 1e-5);
    EXPECT_NEAR(light.directed[0], 0.9875, 1e-5);
    EXPECT_NEAR(light.directed[1], 2 * 0.9875, 1e-5);
    EXPECT_NEAR(light.directed[2], 0.5 * 0.9875, 1e-5);
    EXPECT_NEAR(light.ambient[0], 0.2 + 0.003125, 1e-5);
    EXPECT_NEAR(light.ambient[1], 0.1 + 2 * 0.003125, 1e-5);
    EXPECT_NEAR(light.ambient[2], 0.5 * 0.003125, 1e-5);
}

TEST(ShRuntime, LegacyLightingOfPureAmbientHasNoDirectedPart) {
    const LegacyLighting light = toLegacyLighting(toGridPoint(projectAmbient({0.3, 0.4, 0.5})));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(light.directed[c], 0.0f);
    EXPECT_NEAR(light.ambient[0], 0.3, 1e-6);
    EXPECT_NEAR(light.ambient[2], 0.5, 1e-6);
    EXPECT_EQ(light.direction[2], 1.0f);
}

TEST(ShRuntime, LegacyLightingBeatsAmbientOnlyForTwoLights) {
    // The fitted model must match the SH irradiance better than its own ambient alone.
    SH9Color sh;
    addDirectionalIrradiance(sh, {0, 0, 1}, {1, 1, 1});
    addDirectionalIrradiance(sh, normalized({1, 0, 0.2}), {0.5, 0.5, 0.5});
    const GridPointSH p = toGridPoint(sh);
    const LegacyLighting light = toLegacyLighting(p);
    double fitErr = 0, flatErr = 0;
    for (const Vec3d& n : test::fibonacciSphere(2000)) {
        const double e = evalIrradiance(sh, n).r;
        const double h = std::max(0.0, n.x * light.direction[0] + n.y * light.direction[1] + n.z * light.direction[2]);
        fitErr += std::pow(light.ambient[0] + light.directed[0] * h - e, 2);
        flatErr += std::pow(light.ambient[0] - e, 2);
    }
    EXPECT_LT(fitErr, 0.2 * flatErr);
    EXPECT_GT(light.direction[2], light.direction[0]);  // the brighter light dominates
}

}  // namespace
}  // namespace q3::sh
