// The SH grid in a real engine: ioquake3's renderer with the patch of tools/engine/ioq3-sh lights a
// player model from the BSPX LIGHTGRID_SH lump of -shbspx maps compiled by this build's stages,
// next to the legacy grid (r_shGrid 0), in third person under q3-screenshot. Strict shots: the
// renderer must not warn about the maps. The tests skip, saying why, when the patched renderer
// cannot be built on this machine (no ioquake3 source, client or SDL headers).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include "bspfile.h"
#include "file_io.h"
#include "ioq3_sh_run.h"
#include "test_data.h"

namespace q3::enginetest {
namespace {
namespace fs = std::filesystem;

#define REQUIRE_PATCHED_IOQ3(client)                                                           \
    std::string whyMissing;                                                                    \
    const fs::path client = patchedIoq3(whyMissing);                                           \
    if (client.empty()) GTEST_SKIP() << "skipped: the patched ioquake3 renderer cannot be built here: " << whyMissing

// Every SH shot printed the renderer's own sample at the eye (r_debuglight): it must be what
// libs/sh's runtime samples in the same file at the same point.
void expectSamplesMatchRuntime(const fs::path& bsp, const Shot& shShot) {
    const std::vector<RendererSample> samples = rendererSamples(shShot.log);
    ASSERT_FALSE(samples.empty()) << "the patched renderer printed no SH sample";
    for (const RendererSample& s : samples) {
        const double difference = largestRuntimeDifference(bsp, s);
        // Both sum the 8 corners in double and round once; the printed 9 digits round-trip floats.
        EXPECT_LE(difference, 1e-6) << "at " << s.position[0] << " " << s.position[1] << " " << s.position[2];
    }
    std::cout << "  renderer vs runtime at " << samples.size() << " eye samples: agree\n";
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

// Share of red in red + blue over the model's pixels.
double redShare(const MaskedStats& m) { return m.meanRgb[0] / std::max(1e-9, m.meanRgb[0] + m.meanRgb[2]); }

// A 512 x 512 x 256 room, a red light 224 units to +X of the player and a blue one 224 units to -X,
// same strength. The player stands midway between two legacy grid columns (x = 0 and 64, cell 64),
// where the legacy grid's directions (towards the nearer light) cancel.
std::string twoLightRoom() {
    auto box = [](int x0, int y0, int z0, int x1, int y1, int z1) {
        auto plane = [](int a[3], int b[3], int c[3]) {
            char line[200];
            std::snprintf(line, sizeof line, "( %d %d %d ) ( %d %d %d ) ( %d %d %d ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n",
                          a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]);
            return std::string(line);
        };
        int p[6][3][3] = {{{x0, 0, 0}, {x0, 1, 0}, {x0, 0, 1}}, {{x1, 0, 0}, {x1, 0, 1}, {x1, 1, 0}},
                          {{0, y0, 0}, {0, y0, 1}, {1, y0, 0}}, {{0, y1, 0}, {1, y1, 0}, {0, y1, 1}},
                          {{0, 0, z0}, {1, 0, z0}, {0, 1, z0}}, {{0, 0, z1}, {0, 1, z1}, {1, 0, z1}}};
        std::string s = "{\n";
        for (auto& f : p) s += plane(f[0], f[1], f[2]);
        return s + "}\n";
    };
    const int x0 = -224, x1 = 288, y0 = -256, y1 = 256, z0 = 0, z1 = 256, t = 16;
    std::string map = "{\n\"classname\" \"worldspawn\"\n";
    map += box(x0 - t, y0 - t, z0 - t, x0, y1 + t, z1 + t) + box(x1, y0 - t, z0 - t, x1 + t, y1 + t, z1 + t);
    map += box(x0, y0 - t, z0 - t, x1, y0, z1 + t) + box(x0, y1, z0 - t, x1, y1 + t, z1 + t);
    map += box(x0, y0, z0 - t, x1, y1, z0) + box(x0, y0, z1, x1, y1, z1 + t);
    map += "}\n";
    map += "{\n\"classname\" \"light\"\n\"origin\" \"256 0 64\"\n\"light\" \"500\"\n\"_color\" \"1 0 0\"\n}\n";
    map += "{\n\"classname\" \"light\"\n\"origin\" \"-192 0 64\"\n\"light\" \"500\"\n\"_color\" \"0 0 1\"\n}\n";
    map += "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"32 0 24\"\n\"angle\" \"0\"\n}\n";
    return map;
}

struct SideStats {
    MaskedStats sh, legacy;
};

TEST(ShGridInIoquake3, TwoLightRoomShowsRedAndBlueSides) {
    REQUIRE_PATCHED_IOQ3(client);
    const fs::path dir = test::tempDir();
    const fs::path gameDir = dir / "baseoa";
    fs::create_directories(gameDir / "maps");
    writeFileAtomic(gameDir / "maps" / "shroom.map", twoLightRoom());
    const fs::path bsp = compileWithShBspx(gameDir, "shroom");

    // The player faces the camera, which q3-screenshot puts in front of it (cg_thirdPersonAngle
    // 150): facing +X (yaw 0) the camera sees the side towards the red light, facing -X the blue.
    // setviewpos teleports, and a teleport sends the player off forwards at 400 units/s, which
    // noclip's friction stops after about 44 units: each view starts that far behind x = 32.
    SideStats sides[2];
    const char* views[2] = {"-12 0 33 0", "76 0 33 180"};
    for (int side = 0; side < 2; ++side) {
        const fs::path shots = dir / (side == 0 ? "red-side" : "blue-side");
        const Shot sh = shootThird(client, bsp, views[side], GridChoice::Sh, shots);
        const Shot legacy = shootThird(client, bsp, views[side], GridChoice::Legacy, shots);
        const Shot none = shootThird(client, bsp, views[side], GridChoice::NoModel, shots);
        sides[side] = {modelStats(sh, none), modelStats(legacy, none)};
        expectSamplesMatchRuntime(bsp, sh);
        EXPECT_TRUE(rendererSamples(legacy.log).empty()) << "r_shGrid 0 still sampled the SH grid";
        for (const Shot* s : {&sh, &legacy, &none})
            EXPECT_FALSE(linesWith(s->log, "SH light grid:").empty()) << "the renderer did not load the lump";
        for (const auto& [what, m] : {std::pair{"SH", sides[side].sh}, std::pair{"legacy", sides[side].legacy}})
            std::cout << "  " << (side == 0 ? "red" : "blue") << " side, " << what << " grid: " << m.pixels
                      << " model pixels, mean RGB " << m.meanRgb[0] << " " << m.meanRgb[1] << " " << m.meanRgb[2]
                      << ", red share " << redShare(m) << "\n";
    }
    const SideStats& red = sides[0];
    const SideStats& blue = sides[1];
    for (const SideStats& s : sides) {
        EXPECT_GT(s.sh.pixels, 1000u) << "no model in view";
        EXPECT_GT(s.legacy.pixels, 1000u) << "no model in view";
    }
    // SH: the side towards each light takes its colour (measured: red share 0.81 and 0.28, mean
    // R 32.4 against B 7.8 on the red side, B 25.7 against R 10.1 on the blue side).
    EXPECT_GT(red.sh.meanRgb[0], 2.0 * red.sh.meanRgb[2]);
    EXPECT_GT(blue.sh.meanRgb[2], 2.0 * blue.sh.meanRgb[0]);
    EXPECT_GT(redShare(red.sh) - redShare(blue.sh), 0.4);
    // Legacy: one mixed tint wherever the model is seen from (measured shares 0.58 and 0.54): the
    // two sides differ by less than a fifth of the SH difference.
    EXPECT_LT(std::abs(redShare(red.legacy) - redShare(blue.legacy)),
              0.2 * (redShare(red.sh) - redShare(blue.sh)));
}

// The first five deathmatch spawns of a compiled map, as q3-screenshot views ("X Y Z+9 YAW").
std::vector<std::string> spawnViews(const fs::path& bsp, size_t count) {
    std::vector<std::string> views;
    for (const bsp::Entity& e : bsp::parseEntities(bsp::readBsp(bsp).entities, bsp.string())) {
        if (e.value("classname") != "info_player_deathmatch" || views.size() == count) continue;
        float x = 0, y = 0, z = 0;
        if (std::sscanf(e.value("origin").c_str(), "%f %f %f", &x, &y, &z) != 3) continue;
        const std::string angle = e.value("angle").empty() ? "0" : e.value("angle");
        views.push_back(std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z + 9) + " " + angle);
    }
    return views;
}

const std::string kRealMap = "oacmpdm5";

TEST(ShGridInIoquake3, RealMapBrightnessMatchesLegacyAtFiveSpawns) {
    REQUIRE_PATCHED_IOQ3(client);
    const fs::path dir = test::tempDir();
    const fs::path bsp = compileWithShBspx(stageOacmpMap(dir / "game", kRealMap), kRealMap);
    const std::vector<std::string> views = spawnViews(bsp, test::realBspsAreSampled() ? 2 : 5);
    ASSERT_EQ(views.size(), test::realBspsAreSampled() ? 2u : 5u);
    // The same file without its BSPX trailer: libs/sh's runtime then reads the legacy grid.
    bsp::Bsp legacyOnly = bsp::readBsp(bsp);
    legacyOnly.bspx.clear();
    const fs::path legacyBsp = dir / "legacy-only.bsp";
    bsp::writeBsp(legacyBsp, legacyOnly);
    std::vector<double> ratios;
    for (size_t i = 0; i < views.size(); ++i) {
        struct Measured {
            Shot sh;
            MaskedStats shModel, legacyModel;
            double ratio = 0;
        };
        auto measure = [&](const std::string& attempt) {
            const fs::path shots = dir / ("spawn" + std::to_string(i) + attempt);
            Measured m;
            m.sh = shootThird(client, bsp, views[i], GridChoice::Sh, shots);
            const Shot legacy = shootThird(client, bsp, views[i], GridChoice::Legacy, shots, {"set r_ambientScale 1"});
            const Shot none = shootThird(client, bsp, views[i], GridChoice::NoModel, shots);
            m.shModel = modelStats(m.sh, none);
            m.legacyModel = modelStats(legacy, none);
            m.ratio = m.shModel.meanLuminance / std::max(1e-9, m.legacyModel.meanLuminance);
            std::cout << "  spawn " << i << attempt << " (" << views[i] << "): model luma SH " << m.shModel.meanLuminance
                      << " (" << m.shModel.pixels << " px), legacy " << m.legacyModel.meanLuminance << " ("
                      << m.legacyModel.pixels << " px), ratio " << m.ratio << "\n";
            return m;
        };
        // Every shot runs the game at a fixed 33 ms a frame (shootThird), so the model's idle pose
        // is the same in every run: with real frame times, spawn 1 (a wall hides most of the
        // model) read SH / legacy 0.89-1.13 between runs on a loaded machine; now 0.980 in each.
        const Measured m = measure("");
        const MaskedStats& shModel = m.shModel;
        const MaskedStats& legacyModel = m.legacyModel;
        const Shot& sh = m.sh;
        const double ratio = m.ratio;
        // 0.1% of the frame: at one spawn of oacmpdm5 a wall hides most of the model (676-1725 px).
        EXPECT_GT(shModel.pixels, 300u) << views[i] << ": no model in view";
        EXPECT_GT(legacyModel.pixels, 300u) << views[i] << ": no model in view";
        // Same units as the format states (1.0 = a legacy byte of 255 before the overbright shift),
        // so the legacy shot keeps its ambient at that scale (r_ambientScale 1, not the engine's
        // 0.6), and the renderer saturates the SH sample's ambient and directed parts as ioquake3
        // saturates lump 15's. Measured on oacmpdm5 over five runs: SH / legacy 1.081-1.089,
        // 0.968-1.012, 1.034-1.038, 0.929-0.938, 1.067-1.092 (the idle animation moves a run by up
        // to 2%). Without the saturation: 1.23, 1.01, 1.14, 0.97, 1.17.
        EXPECT_NEAR(ratio, 1.0, 0.10) << views[i];
        ratios.push_back(ratio);
        expectSamplesMatchRuntime(bsp, sh);
        // Where the model's ratio comes from: the two grids' own means at the eye, where the
        // renderer sampled (no engine in between).
        for (const RendererSample& eye : rendererSamples(sh.log))
            std::cout << "    grids at the eye " << eye.position[0] << " " << eye.position[1] << " " << eye.position[2]
                      << ": SH / legacy sphere mean " << gridSphereMean(bsp, eye.position) /
                                                           std::max(1e-9, gridSphereMean(legacyBsp, eye.position))
                      << "\n";
    }
    std::cout << "  mean SH / legacy model luma over " << ratios.size() << " spawns: " << mean(ratios) << "\n";
}

// Writes `map` with its LIGHTGRID_SH payload replaced, returns the file.
fs::path withShPayload(const bsp::Bsp& map, std::vector<uint8_t> payload, const fs::path& path) {
    bsp::Bsp broken = map;
    for (bsp::BspxLump& lump : broken.bspx)
        if (lump.name == "LIGHTGRID_SH") lump.data = std::move(payload);
    fs::create_directories(path.parent_path());
    bsp::writeBsp(path, broken);
    return path;
}

TEST(ShGridInIoquake3, MalformedLumpIsIgnoredWithOneWarning) {
    REQUIRE_PATCHED_IOQ3(client);
    const fs::path dir = test::tempDir();
    const fs::path good = compileWithShBspx(stageOacmpMap(dir / "game", kRealMap), kRealMap);
    const bsp::Bsp map = bsp::readBsp(good);
    const bsp::BspxLump* lump = map.findBspx("LIGHTGRID_SH");
    ASSERT_NE(lump, nullptr);
    ASSERT_GT(lump->data.size(), 40u + 108u);

    std::vector<uint8_t> wrongCount = lump->data;
    wrongCount[36] ^= 1;  // numPoints no longer the gridBounds product
    std::vector<uint8_t> truncated(lump->data.begin(), lump->data.end() - 108);
    std::vector<uint8_t> notFinite = lump->data;
    for (int i = 0; i < 4; ++i) notFinite[40 + 4 * 13 + i] = i < 2 ? 0x00 : (i == 2 ? 0xc0 : 0x7f);  // a NaN
    const std::vector<std::pair<fs::path, std::string>> cases = {
        {withShPayload(map, wrongCount, dir / "count" / "badcount.bsp"), "numPoints"},
        {withShPayload(map, truncated, dir / "short" / "badshort.bsp"), "length"},
        {withShPayload(map, notFinite, dir / "nan" / "badnan.bsp"), "not finite"}};

    const std::string view = spawnViews(good, 1).at(0);
    const Shot legacy = shootThird(client, good, view, GridChoice::Legacy, dir / "good");
    const Shot none = shootThird(client, good, view, GridChoice::NoModel, dir / "good");
    const MaskedStats legacyModel = modelStats(legacy, none);
    for (const auto& [file, reason] : cases) {
        const Shot shot = shootThird(client, file, view, GridChoice::Sh, file.parent_path() / "shots");
        const std::vector<std::string> warnings = linesWith(shot.log, "LIGHTGRID_SH");
        ASSERT_EQ(warnings.size(), 1u) << file << ":\n" << shot.log;
        std::cout << "  " << file.filename().string() << ": " << warnings[0] << "\n";
        EXPECT_NE(warnings[0].find("WARNING"), std::string::npos);
        EXPECT_NE(warnings[0].find(reason), std::string::npos);
        EXPECT_TRUE(linesWith(shot.log, "SH light grid:").empty());
        EXPECT_TRUE(rendererSamples(shot.log).empty()) << "the model was lit from a rejected grid";
        // The map renders as without the lump: the model lit by the legacy grid (the idle
        // animation moves a few pixels between runs, so the means are compared).
        const MaskedStats model = modelStats(shot, none);
        std::cout << "    model luma " << model.meanLuminance << " against " << legacyModel.meanLuminance
                  << " with the legacy grid\n";
        // Measured within 0.02-2.9% over 7 runs; the SH grid lights this model 13-14% brighter
        // (against the engine's own r_ambientScale 0.6).
        EXPECT_NEAR(model.meanLuminance, legacyModel.meanLuminance, 0.06 * legacyModel.meanLuminance);
    }
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Printed, not asserted beyond the runs themselves: the frame time of a fixed camera on the model
// with each grid (com_speeds, frame rate uncapped, the loading frames left out). Two runs of each,
// alternating, since other work on the machine shifts single runs by a third.
TEST(ShGridInIoquake3, FrameCostIsPrinted) {
    REQUIRE_PATCHED_IOQ3(client);
    const fs::path dir = test::tempDir();
    const fs::path bsp = compileWithShBspx(stageOacmpMap(dir / "game", kRealMap), kRealMap);
    const std::string view = spawnViews(bsp, 1).at(0);
    const std::vector<std::string> timing = {"set com_speeds 1", "set com_maxfps 0"};
    std::vector<double> times[2];
    for (int run = 0; run < 4; ++run) {
        const GridChoice grid = run % 2 ? GridChoice::Sh : GridChoice::Legacy;
        // A settle time of 10 s is 301 frames at the script's 30 fps; uncapped they pass sooner.
        const Shot shot = shootThird(client, bsp, view, grid, dir / ("run" + std::to_string(run)), timing, "10");
        const std::vector<double> runTimes = frameTimes(shot.log, 20);
        ASSERT_GT(runTimes.size(), 30u) << "com_speeds printed too few frames";
        times[run % 2].insert(times[run % 2].end(), runTimes.begin(), runTimes.end());
    }
    for (int sh = 0; sh < 2; ++sh)
        std::cout << "  " << (sh ? "SH" : "legacy") << " grid: " << times[sh].size() << " frames, mean "
                  << mean(times[sh]) << " ms, median " << median(times[sh]) << " ms\n";
    std::cout << "  SH / legacy frame time: mean " << mean(times[1]) / mean(times[0]) << ", median "
              << median(times[1]) / median(times[0]) << "\n";
}

}  // namespace
}  // namespace q3::enginetest
