// The SH grid on a real map (oacmpdm1 with its .map): the -light pipeline steps in order plus
// SetupGridSH / TraceGridSH / the write, then the file, the fill near walls, -shprobe, -shimage
// and malformed lumps.
#include <gtest/gtest.h>

#include <cstring>

#include "file_io.h"
#include "grid_sh.h"
#include "light_context.h"
#include "sh_tools.h"
#include "test_data.h"

namespace q3::light {
namespace {

// What one run of the pipeline leaves for the tests below.
struct RealMapRun {
    std::filesystem::path dir;
    ShGridLayout layout;
    sh::GridSH grid;
    ShTraceStats stats;
    std::vector<uint8_t> plainFile;  // -light -fast
    std::vector<uint8_t> shFile;     // -light -fast -sh
    std::vector<bsp::GridPoint> legacyGrid;
};

// The steps of runLightStage (light.cpp) in order, with the SH grid after the legacy grid; written
// twice from the same lighting, once without and once with the SH grid.
RealMapRun runPipeline() {
    RealMapRun run;
    run.dir = test::tempDir();
    const std::filesystem::path maps = run.dir / "baseoa" / "maps";
    std::filesystem::create_directories(maps);
    std::filesystem::copy_file(test::realBsp("oacmpdm1"), maps / "oacmpdm1.bsp");
    std::filesystem::path mapSource;
    for (const auto& p : test::oacmpMapSources())
        if (p.stem() == "oacmpdm1") mapSource = p;
    if (mapSource.empty()) ADD_FAILURE() << "oacmpdm1.map missing from the data cache";
    else std::filesystem::copy_file(mapSource, maps / "oacmpdm1.map");

    CommonOptions common;
    common.mapPath = maps / "oacmpdm1.bsp";
    common.basePaths = {test::openArenaBase().string()};
    common.fsGame = "baseoa";
    common.threads = 2;
    common.commandLine = "-light -fast -nolm maps/oacmpdm1.bsp";
    Log log(false);
    LightContext ctx;
    ctx.options.fast = true;
    ctx.options.noLightmaps = true;  // the grids do not depend on lightmaps; keeps the test quick
    loadLightInputs(ctx, common, log);
    buildSurfaceGeometry(ctx);
    buildScene(ctx);
    createLights(ctx, log);
    lightGrid(ctx, log);
    run.layout = setupGridSH(ctx, log);
    run.grid = traceGridSH(ctx, run.layout, log, &run.stats).decode();
    run.legacyGrid = ctx.bsp.lightGrid;

    const std::vector<bsp::Entity> entities = ctx.entities;
    writeLitBsp(ctx, log);
    run.plainFile = readFileBytes(ctx.bspPath);
    ctx.entities = entities;
    ctx.commandLine = "-light -fast -nolm -sh maps/oacmpdm1.bsp";
    ctx.options.sh = true;
    const ShTraceStats again = lightGridSH(ctx, log);  // the one-call form the stage uses
    if (again.inSolid != run.stats.inSolid || ctx.bsp.shGrid != sh::encodeGridLump(run.grid))
        ADD_FAILURE() << "lightGridSH differs from setupGridSH + traceGridSH";
    ctx.bspPath = maps / "oacmpdm1_sh.bsp";
    writeLitBsp(ctx, log);
    run.shFile = readFileBytes(ctx.bspPath);
    return run;
}

class ShRealMap : public ::testing::Test {
protected:
    static void SetUpTestSuite() { run_ = new RealMapRun(runPipeline()); }
    static void TearDownTestSuite() {
        delete run_;
        run_ = nullptr;
    }
    static RealMapRun* run_;
};
RealMapRun* ShRealMap::run_ = nullptr;

bool isBlack(const sh::GridPointSH& p) {
    for (const auto& c : p.coeffs)
        if (c[0] != 0 || c[1] != 0 || c[2] != 0) return false;
    return true;
}

TEST_F(ShRealMap, NoBlackPointNextToWallsAfterFill) {
    const RealMapRun& r = *run_;
    const auto& b = r.layout.bounds;
    ASSERT_EQ(r.grid.points.size(), r.layout.numPoints());
    ASSERT_EQ(r.stats.solid.size(), r.grid.points.size());
    std::cout << "[ SH grid  ] " << b[0] << " x " << b[1] << " x " << b[2] << ", " << r.stats.nudged << " nudged, "
              << r.stats.inSolid << " in solid, " << r.stats.filled << " filled, black before fill "
              << r.stats.blackBeforeFill << ", after " << r.stats.blackAfterFill << "\n";
    EXPECT_GT(r.stats.inSolid, 0u);
    EXPECT_EQ(r.stats.filled, r.stats.inSolid);
    EXPECT_GE(r.stats.blackBeforeFill, r.stats.inSolid);
    EXPECT_LT(r.stats.blackAfterFill, r.stats.blackBeforeFill);
    // Every point within one cell of a wall: solid points themselves and free points next to one.
    size_t nearWall = 0, blackNearWall = 0;
    for (int z = 0; z < b[2]; ++z)
        for (int y = 0; y < b[1]; ++y)
            for (int x = 0; x < b[0]; ++x) {
                const size_t i = size_t(x) + size_t(y) * b[0] + size_t(z) * b[0] * b[1];
                bool near = r.stats.solid[i] != 0;
                for (int dz = -1; dz <= 1 && !near; ++dz)
                    for (int dy = -1; dy <= 1 && !near; ++dy)
                        for (int dx = -1; dx <= 1 && !near; ++dx) {
                            const int nx = x + dx, ny = y + dy, nz = z + dz;
                            if (nx < 0 || ny < 0 || nz < 0 || nx >= b[0] || ny >= b[1] || nz >= b[2]) continue;
                            near = r.stats.solid[size_t(nx) + size_t(ny) * b[0] + size_t(nz) * b[0] * b[1]] != 0;
                        }
                if (!near) continue;
                ++nearWall;
                if (isBlack(r.grid.points[i])) ++blackNearWall;
            }
    EXPECT_GT(nearWall, 0u);
    EXPECT_EQ(blackNearWall, 0u) << "of " << nearWall << " points within one cell of a wall";
}

TEST_F(ShRealMap, LegacyLumpsUnchangedAndHeaderIsV47) {
    const RealMapRun& r = *run_;
    const bsp::Bsp plain = bsp::parseBsp(r.plainFile, "plain");
    const bsp::Bsp withSh = bsp::parseBsp(r.shFile, "sh");
    EXPECT_EQ(plain.version, 46);
    EXPECT_EQ(withSh.version, 47);
    EXPECT_EQ(withSh.headerLumps, 19);
    int32_t header[2 + 19 * 2];
    std::memcpy(header, r.shFile.data(), sizeof(header));
    EXPECT_EQ(std::memcmp(r.shFile.data(), "IBSP", 4), 0);
    EXPECT_EQ(header[1], 47);
    EXPECT_EQ(header[2 + 17 * 2], 0);  // lump 17 empty
    EXPECT_EQ(header[2 + 17 * 2 + 1], 0);
    EXPECT_EQ(size_t(header[2 + 18 * 2 + 1]), r.layout.lumpBytes());
    EXPECT_EQ(std::memcmp(r.plainFile.data() + 4, "\x2e\0\0\0", 4), 0);
    EXPECT_GE(header[2 + 0 * 2], 160);  // the first lump follows the 160-byte header
    for (int lump = 1; lump <= 16; ++lump)
        EXPECT_EQ(bsp::lumpBytes(plain, lump), bsp::lumpBytes(withSh, lump)) << "lump " << lump;
    EXPECT_EQ(withSh.shGrid, sh::encodeGridLump(r.grid));
    // Lump 0: the same entities except the recorded command line.
    std::vector<bsp::Entity> a = bsp::parseEntities(plain.entities, "plain");
    std::vector<bsp::Entity> c = bsp::parseEntities(withSh.entities, "sh");
    ASSERT_EQ(a.size(), c.size());
    EXPECT_NE(a[0].value("_q3map2_cmdline"), c[0].value("_q3map2_cmdline"));
    EXPECT_NE(c[0].value("_q3map2_cmdline").find("-sh"), std::string::npos);
    a[0].set("_q3map2_cmdline", "");
    c[0].set("_q3map2_cmdline", "");
    EXPECT_EQ(bsp::unparseEntities(a), bsp::unparseEntities(c));
}

TEST_F(ShRealMap, ProbeMatchesGridAndLegacy) {
    const RealMapRun& r = *run_;
    // A free, lit grid point in the middle of the map: the probe there is the point itself.
    const auto& b = r.layout.bounds;
    size_t chosen = SIZE_MAX;
    for (size_t i = r.grid.points.size() / 2; i < r.grid.points.size(); ++i)
        if (!r.stats.solid[i] && r.grid.points[i].coeffs[0][0] > 0.05f && r.legacyGrid.size() > 0) {
            chosen = i;
            break;
        }
    ASSERT_NE(chosen, SIZE_MAX);
    const int x = int(chosen % size_t(b[0])), y = int((chosen / size_t(b[0])) % size_t(b[1])),
              z = int(chosen / (size_t(b[0]) * b[1]));
    const Vec3 at = r.layout.pointOrigin(x, y, z);
    const float position[3] = {at.x, at.y, at.z};
    const shtools::ProbeReport report = shtools::probeBsp(r.shFile, position, "oacmpdm1_sh.bsp");
    EXPECT_EQ(report.source, sh::GridSource::Lump18);
    for (int k = 0; k < 9; ++k)
        for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(report.sh.coeffs[k][ch], r.grid.points[chosen].coeffs[k][ch]);
    EXPECT_TRUE(report.hasLegacy);
    const std::vector<std::string> lines = shtools::formatProbeReport(report);
    EXPECT_EQ(lines.size(), 1u + 1u + 9u + 1u + 6u + 1u + 1u);
    EXPECT_NE(lines[lines.size() - 2].find("legacy grid: ambient"), std::string::npos);
    EXPECT_EQ(lines.back(), "light cache: no WORLDLIGHTS lump (-light -worldlights)");
    // The legacy lighting of the same spot and the SH agree on the overall level within a factor.
    double shSum = 0, legacySum = 0;
    for (int f = 0; f < 6; ++f)
        for (int ch = 0; ch < 3; ++ch) {
            shSum += report.shFaces.face[f][ch];
            legacySum += report.legacyFaces.face[f][ch];
        }
    EXPECT_GT(shSum, 0);
    EXPECT_GT(legacySum, 0);

    // Without an SH grid, -shprobe says so.
    try {
        shtools::probeBsp(r.plainFile, position, "plain.bsp");
        FAIL() << "no error";
    } catch (const bsp::BspError& e) {
        EXPECT_NE(std::string(e.what()).find("plain.bsp: no SH light grid"), std::string::npos) << e.what();
    }
}

TEST_F(ShRealMap, ImageShowsShadedProbes) {
    const RealMapRun& r = *run_;
    const std::filesystem::path bspPath = run_->dir / "baseoa" / "maps" / "oacmpdm1_sh.bsp";
    const std::filesystem::path png = run_->dir / "probes.png";
    shtools::ShImageOptions options;
    const std::string map = shtools::parseShImageArguments(
        std::vector<std::string>{bspPath.string(), png.string()}, options);
    EXPECT_EQ(map, bspPath.string());
    EXPECT_FALSE(options.heightSet);
    CommonOptions common;
    common.mapPath = bspPath;
    Log log(false);
    ASSERT_EQ(shtools::runShImageStage(options, common, log), 0);
    const std::vector<uint8_t> bytes = readFileBytes(png);
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(std::memcmp(bytes.data(), "\x89PNG", 4), 0);

    sh::GridRuntime runtime;
    runtime.setGrid(r.grid, sh::GridSource::Lump18);
    const Image image = shtools::renderProbeImage(runtime, shtools::middleHeight(r.grid), 8, 1);
    EXPECT_EQ(image.width, r.layout.bounds[0] * 8);
    EXPECT_EQ(image.height, r.layout.bounds[1] * 8);
    size_t lit = 0, background = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* t = image.texel(x, y);
            if (t[0] == 32 && t[1] == 32 && t[2] == 32) ++background;
            else if (t[0] + t[1] + t[2] > 0) ++lit;
        }
    EXPECT_GT(background, 0u);  // corners outside the discs
    EXPECT_GT(lit, size_t(image.width) * image.height / 4);
}

TEST_F(ShRealMap, MalformedShLumpsAreRejected) {
    const RealMapRun& r = *run_;
    int32_t offset18 = 0, length18 = 0;
    std::memcpy(&offset18, r.shFile.data() + 8 + 18 * 8, 4);
    std::memcpy(&length18, r.shFile.data() + 8 + 18 * 8 + 4, 4);
    ASSERT_GT(length18, 40);
    auto expectRejected = [&](std::vector<uint8_t> bytes, const char* what) {
        EXPECT_THROW(bsp::parseBsp(bytes, "bad.bsp"), bsp::BspError) << what;
        sh::GridRuntime runtime;
        const std::string err = runtime.loadFromBsp(bytes.data(), bytes.size(), "bad.bsp");
        EXPECT_FALSE(err.empty()) << what;
        EXPECT_EQ(err.find('\n'), std::string::npos) << err;
        const float at[3] = {0, 0, 0};
        EXPECT_THROW(shtools::probeBsp(bytes, at, "bad.bsp"), bsp::BspError) << what;
    };
    {
        std::vector<uint8_t> bytes = r.shFile;
        int32_t numPoints;
        std::memcpy(&numPoints, bytes.data() + offset18 + 36, 4);
        ++numPoints;
        std::memcpy(bytes.data() + offset18 + 36, &numPoints, 4);
        expectRejected(bytes, "numPoints off by one");
    }
    {
        std::vector<uint8_t> bytes = r.shFile;
        const int32_t shorter = length18 - 108;
        std::memcpy(bytes.data() + 8 + 18 * 8 + 4, &shorter, 4);
        expectRejected(bytes, "lump one point short");
    }
    {
        std::vector<uint8_t> bytes = r.shFile;
        const float nan = std::nanf("");
        std::memcpy(bytes.data() + offset18 + 40 + 4, &nan, 4);
        expectRejected(bytes, "NaN coefficient");
    }
    {
        std::vector<uint8_t> bytes = r.shFile;
        const float zero = 0;
        std::memcpy(bytes.data() + offset18 + 12, &zero, 4);
        expectRejected(bytes, "zero cell size");
    }
}

TEST(ShToolsArguments, PositionalFormsAndErrors) {
    shtools::ShProbeOptions probe;
    EXPECT_EQ(shtools::parseShProbeArguments(std::vector<std::string>{"maps/a.bsp", "1", "-2.5", "64"}, probe),
              "maps/a.bsp");
    EXPECT_TRUE(probe.positionSet);
    EXPECT_EQ(probe.position[1], -2.5f);
    EXPECT_THROW(shtools::parseShProbeArguments(std::vector<std::string>{"maps/a.bsp", "1", "2"}, probe),
                 cli::UsageError);
    EXPECT_THROW(shtools::parseShProbeArguments(std::vector<std::string>{"maps/a.bsp", "1", "x", "2"}, probe),
                 cli::UsageError);
    shtools::ShImageOptions image;
    EXPECT_EQ(shtools::parseShImageArguments(std::vector<std::string>{"a.bsp", "o.png", "128"}, image), "a.bsp");
    EXPECT_TRUE(image.heightSet);
    EXPECT_EQ(image.height, 128.0f);
    EXPECT_THROW(shtools::parseShImageArguments(std::vector<std::string>{"a.bsp"}, image), cli::UsageError);
    EXPECT_THROW(shtools::parseShImageArguments(std::vector<std::string>{"a.bsp", "o.png", "nan"}, image),
                 cli::UsageError);
    CommonOptions common;
    common.mapPath = "a.bsp";
    Log log(false);
    EXPECT_THROW(shtools::runShProbeStage(shtools::ShProbeOptions{}, common, log), cli::UsageError);
    EXPECT_THROW(shtools::runShImageStage(shtools::ShImageOptions{}, common, log), cli::UsageError);
    EXPECT_EQ(shtools::shProbeOptionTable().size(), 1u);
    EXPECT_EQ(shtools::shImageOptionTable().size(), 4u);
}

}  // namespace
}  // namespace q3::light
