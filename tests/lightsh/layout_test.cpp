// SetupGridSH: cell size from -gridsh, -gridscalesh and worldspawn gridsize, the 8-unit floor, the
// bounds rule and the growth that keeps lump 18 within its cap.
#include <gtest/gtest.h>

#include <cmath>

#include "../light/light_test_util.h"
#include "grid_sh.h"
#include "light_context.h"

namespace q3::light {
namespace {

std::unique_ptr<LightContext> contextWithWorld(Vec3 mins, Vec3 maxs, const char* gridSize = nullptr) {
    auto ctx = std::make_unique<LightContext>();
    bsp::Model world{};
    mins.toArray(world.mins);
    maxs.toArray(world.maxs);
    ctx->bsp.models.push_back(world);
    bsp::Entity worldspawn = test::entity({{"classname", "worldspawn"}});
    if (gridSize) worldspawn.set("gridsize", gridSize);
    ctx->entities.push_back(worldspawn);
    ctx->bspPath = "maps/layout.bsp";
    return ctx;
}

// The rule of specs/sh-grid.md, written out independently.
void expectBoundsRule(const ShGridLayout& layout, Vec3 worldMins, Vec3 worldMaxs) {
    for (int axis = 0; axis < 3; ++axis) {
        const double s = layout.size[axis];
        const double lo = s * std::ceil(double(worldMins[axis]) / s);
        const double hi = s * std::floor(double(worldMaxs[axis]) / s);
        EXPECT_EQ(layout.mins[axis], float(lo)) << "axis " << axis;
        EXPECT_EQ(layout.bounds[axis], int(std::lround((hi - lo) / s)) + 1) << "axis " << axis;
    }
}

TEST(ShGridLayout, DefaultIsLegacyCellOverTwo) {
    auto ctx = contextWithWorld({-100, -50, -30}, {300, 200, 100});
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    EXPECT_EQ(layout.size, (Vec3{32, 32, 64}));
    EXPECT_EQ(layout.mins, (Vec3{-96, -32, 0}));
    EXPECT_EQ(layout.bounds, (std::array<int, 3>{13, 8, 2}));
    EXPECT_EQ(layout.numPoints(), 13u * 8u * 2u);
    EXPECT_EQ(layout.lumpBytes(), 40u + 108u * 13u * 8u * 2u);
    EXPECT_TRUE(log.warnings.empty());
    expectBoundsRule(layout, {-100, -50, -30}, {300, 200, 100});
}

TEST(ShGridLayout, GridScaleShFour) {
    auto ctx = contextWithWorld({0, 0, 0}, {256, 256, 256});
    ctx->options.gridScaleSH = 4;
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    EXPECT_EQ(layout.size, (Vec3{16, 16, 32}));
    EXPECT_EQ(layout.bounds, (std::array<int, 3>{17, 17, 9}));
}

TEST(ShGridLayout, ExplicitGridShOverridesScale) {
    auto ctx = contextWithWorld({-10, -10, -10}, {250, 130, 300}, "32 32 32");
    ctx->options.gridScaleSH = 4;
    ctx->options.gridSizeSH[0] = 24;
    ctx->options.gridSizeSH[1] = 24;
    ctx->options.gridSizeSH[2] = 48;
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    EXPECT_EQ(layout.size, (Vec3{24, 24, 48}));
    EXPECT_EQ(layout.mins, (Vec3{0, 0, 0}));
    EXPECT_EQ(layout.bounds, (std::array<int, 3>{11, 6, 7}));  // 240/24+1, 120/24+1, 288/48+1
    expectBoundsRule(layout, {-10, -10, -10}, {250, 130, 300});
}

TEST(ShGridLayout, WorldspawnGridSizeIsTheBase) {
    auto ctx = contextWithWorld({0, 0, 0}, {1024, 1024, 512}, "128 96 256");
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    EXPECT_EQ(layout.size, (Vec3{64, 48, 128}));
    expectBoundsRule(layout, {0, 0, 0}, {1024, 1024, 512});
    ctx->options.gridScaleSH = 3;  // cells need not be whole units
    const ShGridLayout third = setupGridSH(*ctx, log.log);
    EXPECT_FLOAT_EQ(third.size.x, 128.0f / 3.0f);
    expectBoundsRule(third, {0, 0, 0}, {1024, 1024, 512});
}

TEST(ShGridLayout, EachAxisAtLeastEightWithWarning) {
    auto ctx = contextWithWorld({0, 0, 0}, {64, 64, 64}, "8 8 64");
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);  // 8/2 = 4 on x and y
    EXPECT_EQ(layout.requestedSize, (Vec3{4, 4, 32}));
    EXPECT_EQ(layout.size, (Vec3{8, 8, 32}));
    EXPECT_TRUE(layout.clamped);
    ASSERT_EQ(log.warnings.size(), 1u);
    EXPECT_NE(log.warnings[0].find("8 8 32"), std::string::npos) << log.warnings[0];

    ctx->options.gridSizeSH[0] = 2;
    ctx->options.gridSizeSH[1] = 24;
    ctx->options.gridSizeSH[2] = 7.5f;
    test::CapturingLog log2;
    const ShGridLayout explicitLayout = setupGridSH(*ctx, log2.log);
    EXPECT_EQ(explicitLayout.size, (Vec3{8, 24, 8}));
    EXPECT_EQ(log2.warnings.size(), 1u);
}

TEST(ShGridLayout, GrowsPastOneGibWithWarningNamingTheSize) {
    // A huge synthetic world: 8-unit cells would need far more than the cap.
    const Vec3 mins{-500000, -500000, -60000}, maxs{500000, 500000, 60000};
    auto ctx = contextWithWorld(mins, maxs);
    ctx->options.gridSizeSH[0] = ctx->options.gridSizeSH[1] = ctx->options.gridSizeSH[2] = 8;
    test::CapturingLog log;
    const ShGridLayout layout = setupGridSH(*ctx, log.log);
    EXPECT_GT(layout.growSteps, 0);
    EXPECT_LE(layout.lumpBytes(), kMaxShLumpBytes);
    const float grown = 8.0f + 8.0f * float(layout.growSteps);
    EXPECT_EQ(layout.size, Vec3::splat(grown));
    expectBoundsRule(layout, mins, maxs);
    // One step less would not fit: the growth stops at the first size that does.
    const ShGridLayout smaller = computeShGridLayout(Vec3::splat(grown - 8.0f), mins, maxs, UINT64_MAX);
    EXPECT_GT(smaller.lumpBytes(), kMaxShLumpBytes);
    ASSERT_EQ(log.warnings.size(), 1u);
    char expected[64];
    std::snprintf(expected, sizeof(expected), "%g %g %g", grown, grown, grown);
    EXPECT_NE(log.warnings[0].find(expected), std::string::npos) << log.warnings[0];
}

TEST(ShGridLayout, SmallLimitGrowsEveryAxisByEight) {
    const ShGridLayout layout = computeShGridLayout({8, 8, 8}, {0, 0, 0}, {64, 64, 64}, 40 + 108 * 27);
    EXPECT_EQ(layout.size, (Vec3{24, 24, 24}));  // 0, 24, 48: 3 points per axis
    EXPECT_EQ(layout.growSteps, 2);
    EXPECT_EQ(layout.numPoints(), 27u);
}

TEST(ShGridLayout, TinyWorldStillHasOnePoint) {
    const ShGridLayout layout = computeShGridLayout({64, 64, 64}, {10, 10, 10}, {20, 20, 20});
    EXPECT_EQ(layout.bounds, (std::array<int, 3>{1, 1, 1}));
}

TEST(ShGridLayout, MalformedGridSizeIsAnError) {
    auto ctx = contextWithWorld({0, 0, 0}, {64, 64, 64}, "64 sixty 128");
    test::CapturingLog log;
    try {
        setupGridSH(*ctx, log.log);
        FAIL() << "no error";
    } catch (const CompileError& e) {
        EXPECT_NE(std::string(e.what()).find("maps/layout.bsp"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("gridsize"), std::string::npos) << e.what();
    }
}

TEST(ShGridLayout, OptionsParseAndRefuseBadValues) {
    const auto& table = lightOptionTable();
    auto find = [&](const std::string& name) {
        for (const auto& o : table)
            for (const auto& n : o.info.names)
                if (n == name) return &o;
        return static_cast<const cli::Option<LightOptions>*>(nullptr);
    };
    for (const char* name : {"-sh", "-shbspx", "-gridscalesh", "-gridsh"}) {
        const auto* o = find(name);
        ASSERT_NE(o, nullptr) << name;
        EXPECT_TRUE(o->info.implemented) << name;
    }
    for (const auto& arg : find("-gridsh")->info.args) {
        EXPECT_FALSE(arg.range.contains(0));
        EXPECT_FALSE(arg.range.contains(-8));
        EXPECT_TRUE(arg.range.contains(24));
    }
    EXPECT_FALSE(find("-gridscalesh")->info.args[0].range.contains(0));
    EXPECT_EQ(find("-gridsh")->info.requiredArgs, 3);
}

}  // namespace
}  // namespace q3::light
