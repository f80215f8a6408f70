// The release options (`-light -fast -samples 2 -bounce 2 -patchshadows -dirty -deluxe`, with
// `-nocollapse` so that the runs with and without bounces pack alike) on a real oacmp map, in
// real engines: the relit map loads in ioquake3 and DarkPlaces under the strict
// checks, its deluxe maps follow the layout both engines expect (an even number of pages in lump
// 14, colour and direction interleaved, every lightmapped surface on an even page, worldspawn
// `deluxeMaps 1`), and the same view is measurably brighter with `-bounce 2` than without it, in
// ioquake3's lightmap-only mode and in DarkPlaces'.
//
// DarkPlaces says nothing about deluxe maps when it takes them (with developer 1 and
// developer_loading 1 it prints only "Using internal lightmaps"); what it does print about a bad
// lightmap lump ("Mod_Q3BSP_LoadLightmaps: ...", "invalid ...") fails the strict checks, and its
// lightmap view below is drawn from the interleaved pages.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "bspfile.h"
#include "engine_picture.h"
#include "engine_run.h"
#include "test_data.h"

namespace q3::enginetest {
namespace {
namespace fs = std::filesystem;

// The cheapest oacmp map (about 7 CPU seconds with these options, 4 without the bounces).
const std::string kMap = "oacmpdm5";
const std::vector<std::string> kReleaseOptions = {"-fast", "-samples", "2", "-bounce", "2",
                                                  "-patchshadows", "-dirty", "-deluxe"};

std::vector<std::string> withoutBounce(const std::vector<std::string>& options) {
    std::vector<std::string> out;
    for (size_t i = 0; i < options.size(); ++i) {
        if (options[i] == "-bounce") {
            ++i;  // and its count
            continue;
        }
        out.push_back(options[i]);
    }
    return out;
}

// Relights a fresh copy of the shipped map in <dir>/<tag>; returns the lit BSP's path and prints the
// compiler's bounce lines.
fs::path relight(const fs::path& dir, const std::string& tag, const std::vector<std::string>& options,
                 std::vector<std::string>* bounceLines) {
    std::string output;
    const fs::path lit = relightOacmpMap(dir / tag, kMap, options, &output);
    *bounceLines = linesWith(output, "diffuse lights from");
    for (const std::string& line : *bounceLines) std::cout << "  " << tag << ": " << line << "\n";
    return lit;
}

// Mean byte value of the even (colour) or odd (direction) pages of lump 14.
double meanOfPages(const bsp::Bsp& map, bool odd) {
    const size_t pages = map.lightmaps.size() / bsp::kLightmapPageBytes;
    double sum = 0;
    size_t count = 0;
    for (size_t page = odd ? 1 : 0; page < pages; page += 2) {
        const auto first = map.lightmaps.begin() + std::ptrdiff_t(page * bsp::kLightmapPageBytes);
        for (auto it = first; it != first + bsp::kLightmapPageBytes; ++it) sum += *it;
        count += bsp::kLightmapPageBytes;
    }
    return count ? sum / double(count) : 0;
}

// Mean byte of the colour texels the lightmapped vertices sample: unlike a mean over whole pages,
// it does not depend on how the lightmaps were packed (a run whose lightmaps are less often
// uniform, stored as one texel, fills more pages).
double meanAtVertices(const bsp::Bsp& map) {
    double sum = 0;
    size_t count = 0;
    for (const bsp::Surface& s : map.surfaces) {
        if (s.lightmapNum < 0) continue;
        for (int v = 0; v < s.numVerts; ++v) {
            const bsp::DrawVert& dv = map.drawVerts.at(size_t(s.firstVert + v));
            const int x = std::clamp(int(dv.lightmap[0] * 128), 0, 127);
            const int y = std::clamp(int(dv.lightmap[1] * 128), 0, 127);
            const size_t at = size_t(s.lightmapNum) * bsp::kLightmapPageBytes + (size_t(y) * 128 + size_t(x)) * 3;
            if (at + 2 >= map.lightmaps.size()) continue;
            sum += double(map.lightmaps[at]) + map.lightmaps[at + 1] + map.lightmaps[at + 2];
            count += 3;
        }
    }
    return count ? sum / double(count) : 0;
}

// The deluxe layout both engines rely on.
void expectDeluxeLayout(const bsp::Bsp& map) {
    EXPECT_EQ(map.version, bsp::kVersionQ3);
    ASSERT_FALSE(map.lightmaps.empty());
    ASSERT_EQ(map.lightmaps.size() % bsp::kLightmapPageBytes, 0u) << "lump 14 is not whole 128x128 pages";
    const size_t pages = map.lightmaps.size() / bsp::kLightmapPageBytes;
    EXPECT_EQ(pages % 2, 0u) << pages << " pages: every colour page needs its direction page";
    size_t lightmapped = 0, odd = 0, outside = 0;
    for (const bsp::Surface& s : map.surfaces) {
        if (s.lightmapNum < 0) continue;
        ++lightmapped;
        if (s.lightmapNum % 2 != 0) ++odd;
        if (size_t(s.lightmapNum) + 1 >= pages) ++outside;
    }
    std::cout << "  lump 14: " << pages << " pages, " << lightmapped << " lightmapped surfaces\n";
    EXPECT_GT(lightmapped, 100u);
    EXPECT_EQ(odd, 0u) << "surfaces on an odd (direction) page";
    EXPECT_EQ(outside, 0u) << "surfaces whose page or its direction page lies past lump 14";

    const std::vector<bsp::Entity> entities = bsp::parseEntities(map.entities, kMap);
    ASSERT_FALSE(entities.empty());
    EXPECT_EQ(entities[0].value("deluxeMaps"), "1") << "model-space deluxe maps are announced in worldspawn";

    // Direction pages hold unit vectors encoded as dir * 127.5 + 127.5 (measured mean byte 142,
    // the colour pages 10.5): a direction page filled with colour or left black would fail this.
    const double colour = meanOfPages(map, false), direction = meanOfPages(map, true);
    std::cout << "  mean byte: colour pages " << colour << ", direction pages " << direction << "\n";
    EXPECT_GT(direction, 100.0);
    EXPECT_LT(direction, 190.0);
    EXPECT_GT(direction, 3 * colour);
}

// How much brighter the bounced view must be. Measured on oacmpdm5's first spawn view, 640x480
// lightmap-only mode: ioquake3 mean luma 83.6 with -bounce 2 against 76.8 without (+6.7, 8.8%),
// 53% of the pixels brighter by more than 2 and 0.04% darker; DarkPlaces 34.4 against 32.4 (+2.0,
// 6.1%; its lit share grows from 69% to 81%), 45% of the pixels brighter and none darker. The
// floors sit at about a third of those gains, far above rasteriser noise (identical lightmaps give
// 0 and no changed pixel).
constexpr double kMinIoq3LumaGain = 2.0, kMinDpLumaGain = 0.6;
constexpr double kMinBrighterShare = 0.15;
// Bounced light only adds: far more pixels must brighten than darken.
constexpr double kMinBrighterToDarker = 20.0;

TEST(ReleaseOptionsInEngines, DeluxeLayoutLoadsAndBounceBrightensTheView) {
    const fs::path dir = test::tempDir();
    std::vector<std::string> bounced, plainLines;
    // Both runs keep every lightmap at full size (-nocollapse), so that they pack alike. Otherwise
    // a lightmap that is uniform in one run and not in the other (stored as one texel, or not)
    // moves the others on their pages, and ioquake3 draws some of the moved ones differently (a
    // pillar face of the view darker by half with the same texels elsewhere on the page), which
    // says nothing of the bounces.
    std::vector<std::string> options = kReleaseOptions;
    options.push_back("-nocollapse");
    const fs::path releasePath = relight(dir, "release", options, &bounced);
    const fs::path plainPath = relight(dir, "nobounce", withoutBounce(options), &plainLines);
    EXPECT_EQ(bounced.size(), 2u) << "two radiosity passes";
    EXPECT_TRUE(plainLines.empty());

    const bsp::Bsp release = bsp::readBsp(releasePath);
    const bsp::Bsp plain = bsp::readBsp(plainPath);
    {
        SCOPED_TRACE("release");
        expectDeluxeLayout(release);
    }
    {
        SCOPED_TRACE("without -bounce");
        expectDeluxeLayout(plain);
    }
    EXPECT_GT(meanAtVertices(release), meanAtVertices(plain)) << "bounced light adds to the lightmaps";

    // The engines see the files under names no package ships.
    const fs::path engineDir = dir / "engine";
    const fs::path releaseCopy = copyForEngines(releasePath, engineDir, kMap + "_release");
    const fs::path plainCopy = copyForEngines(plainPath, engineDir, kMap + "_nobounce");

    expectLoads(releaseCopy, "ioq3,dp", engineDir / "logs");

    const RunResult releaseShots =
        runScreenshot(releaseCopy, "ioq3,dp", "lightmap", engineDir / "release", engineDir / "logs");
    std::cout << releaseShots.output;
    ASSERT_EQ(releaseShots.status, 0) << releaseShots.command;
    const RunResult plainShots =
        runScreenshot(plainCopy, "ioq3,dp", "lightmap", engineDir / "nobounce", engineDir / "logs");
    ASSERT_EQ(plainShots.status, 0) << plainShots.command << "\n" << plainShots.output;

    for (const std::string engine : {"ioq3", "dp"}) {
        const Image withBounce = readPng(screenshotPath(engineDir / "release", engine, "lightmap"));
        const Image noBounce = readPng(screenshotPath(engineDir / "nobounce", engine, "lightmap"));
        const PictureStats a = pictureStats(noBounce), b = pictureStats(withBounce);
        const LumaShift shift = lumaShift(noBounce, withBounce, 2.0);
        std::cout << "  " << engine << " lightmap view: luma " << a.meanLuminance << " -> " << b.meanLuminance
                  << ", lit share " << 100 * a.litFraction << "% -> " << 100 * b.litFraction << "%, "
                  << shift.brighter << " pixels brighter, " << shift.darker << " darker\n";
        EXPECT_GT(shift.meanChange, engine == std::string("ioq3") ? kMinIoq3LumaGain : kMinDpLumaGain) << engine;
        EXPECT_GT(double(shift.brighter), kMinBrighterShare * double(b.pixels)) << engine;
        EXPECT_GT(double(shift.brighter), kMinBrighterToDarker * double(shift.darker)) << engine;
    }
}

}  // namespace
}  // namespace q3::enginetest
