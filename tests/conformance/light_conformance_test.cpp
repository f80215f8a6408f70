// Light conformance on real maps: the reference q3map2 compiles an oacmp .map (-bsp -meta, then
// -vis -fast; cached under the data cache; ours for the ownBsp cases), then lights it twice (-threads 2, and -threads 1 for
// the grid mask) while ours lights a copy of the same fresh BSP; lightcompare's figures must stay
// within the limits below. Without the reference binary the tests skip (fail when $CI is set).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>

#include "conformance_pipeline.h"
#include "reference_fixture.h"
#include "light_compare.h"
#include "test_data.h"

namespace q3::conformance {
namespace {
namespace fs = std::filesystem;

// The tolerances (the goal) are the defaults; a map whose figures do not meet one yet
// carries the limit its current figures allow, with the measured value beside it. Limits are
// one-sided: a figure that moves towards the reference always passes.
struct Limits {
    double lightmapRatio = 0.03;          // |total ratio - 1|
    double lightmapCorrelation = 0.99;    // per-surface means
    double classRatio = 0.05;             // |class ratio - 1|, every class with surfaces ...
    std::map<std::string, double> classRatioOf;  // ... unless named here
    double gridAmbient = 0.03;            // |ratio - 1| over the points the reference repeats
    double gridDirected = 0.03;
    double gridAmbientCorrelation = 0.98;   // per-point sums
    double gridDirectedCorrelation = 0.98;
    double gridDirection = 0.95;          // share of lit points within 15 degrees of the reference
    // Over every point, against the reference's -threads 1 run, whose in-solid points ours places
    // the same way (ambient and directed).
    double gridOneThreadCorrelation = 0.98;
    double vertexRatio = 0.05;            // |ratio - 1|
    double lightmappedCount = 0.02;       // |ours - reference| / reference lightmapped surfaces
};

struct MapCase {
    const char* map;
    std::vector<std::string> options;
    Limits limits;
    bool ownBsp = false;  // the BSP and .srf from ours -bsp -meta and -vis -fast, not the reference's
};

// gtest prints the parameter of a failed case; the map and options say it all.
void PrintTo(const MapCase& c, std::ostream* os) {
    *os << c.map;
    for (const std::string& o : c.options) *os << ' ' << o;
}

std::vector<MapCase> cases() {
    std::vector<MapCase> out;
    // Every tolerance of the issue holds (measured at -fast): lightmaps 1.013, correlation 0.9997,
    // classes within 3.3 % (patch 1.033), vertex colours 1.027, grid 1.007 / 1.005, correlations
    // 0.998 / 0.9994, directions 99.0 %.
    out.push_back(MapCase{"oacmpdm1", {"-fast"}, {}});
    // Every tolerance holds: lightmaps 0.996, correlation 0.9957, classes within 1.6 % (shadow
    // 0.984), grid 1.000 / 1.000, correlations 0.9997 / 0.9996, directions 99.9 %, vertex colours
    // 1.000.
    out.push_back(MapCase{"oacmpdm5", {"-fast"}, {}});
    {
        // 1,400 area lights (ceiling fixtures with a q3map_lightimage colour) and few entity lights;
        // 71 % of its grid lies in solid, where q3map2 nudges points at random. Measured at -fast:
        // lightmaps 1.005, correlation 0.997, classes within 0.1 %, grid 0.999 / 0.999,
        // correlations 1.000 / 1.000, directions 99.6 %; against the -threads 1 reference's whole
        // grid 0.9999 / 0.9998 (0.87 / 0.98 while in-solid points took a fixed search).
        MapCase c{"oacmpctf2", {"-fast"}, {}};
        c.limits.gridOneThreadCorrelation = 0.999;
        out.push_back(c);
    }
    // Radiosity: every tolerance holds (lightmaps 0.995, correlation 0.995, shadow class 0.952,
    // vertex colours 0.999, grid 1.000 / 1.000).
    out.push_back(MapCase{"oacmpdm5", {"-fast", "-bounce", "1"}, {}});
    // Dirtmapping: every tolerance holds (lightmaps 1.008, correlation 0.9997, patch class 1.036,
    // vertex colours 1.045, grid 1.008 / 1.006).
    out.push_back(MapCase{"oacmpdm1", {"-fast", "-dirty"}, {}});
    // Sun and sky light: the only map here with a sky-lit class. Every tolerance holds (measured at
    // -fast): lightmaps 0.999, correlation 0.9995, shadow 0.984 (thin ceiling strips whose twin
    // lightmaps share texels), patch 1.023, vertex colours 0.996, grid 1.000 / 0.999.
    out.push_back(MapCase{"oacmpdm4", {"-fast"}, {}});
    {
        // Adaptive sub-sampling: a luxel's sub-samples test the PVS with the first one's cluster,
        // so those after a first one in solid see no light but the sun's. Measured at -fast
        // -samples 2: lightmaps 1.011, correlation 0.9997 (1.030 and 0.995 while each sub-sample
        // used its own cluster).
        MapCase c{"oacmpdm1", {"-fast", "-samples", "2"}, {}};
        c.limits.lightmapRatio = 0.02;
        c.limits.lightmapCorrelation = 0.998;
        out.push_back(c);
    }
    // -compensate 2 halves the light into bytes: q3map2 finds solid and twin lightmaps on the light,
    // so its tolerances span half as many bytes. Every tolerance holds: lightmaps 1.012,
    // correlation 0.9998, shadow class 1.032 (0.932 while twins were found on bytes).
    out.push_back(MapCase{"oacmpdm1", {"-fast", "-compensate", "2"}, {}});
    // On our own -bsp -meta and -vis -fast output: the .srf and BSP drive both -light stages alike.
    // Every tolerance holds (measured at -fast): oacmpdm5 lightmaps 0.998, correlation 0.9995,
    // classes within 1.2 % (patch 0.988), grid 0.999 / 1.000, vertex colours 1.000; oacmpdm1
    // lightmaps 1.013, correlation 0.9997, classes within 3.3 % (patch 1.033), grid 1.008 / 1.006,
    // vertex colours 1.028 - the same figures as on the reference's BSP. oacmpdm10 (worldspawn
    // "ambient" 2, "_color" 0.87 0.87 0.5: the .srf default block's ambientColor, which both -light
    // stages give every lightmap): lightmaps 0.999, patch 1.001, vertex colours 1.000 (1.060, shadow
    // class 2.43 and 1.036 while our .srf wrote a zero ambient and our -light used the worldspawn's).
    // A sampled (sanitizer) run keeps oacmpdm10 alone.
    const std::vector<const char*> ownBspMaps = test::realBspsAreSampled()
                                                    ? std::vector<const char*>{"oacmpdm10"}
                                                    : std::vector<const char*>{"oacmpdm5", "oacmpdm1", "oacmpdm10"};
    for (const char* map : ownBspMaps) {
        MapCase c{map, {"-fast"}, {}};
        c.ownBsp = true;
        out.push_back(c);
    }
    return out;
}

std::string caseName(const ::testing::TestParamInfo<MapCase>& info) {
    std::string name = info.param.map;
    for (const std::string& o : info.param.options) {
        name += '_';
        name += o.substr(o.find_first_not_of('-'));
    }
    if (info.param.ownBsp) name += "_ownBsp";
    return name;
}

fs::path mapSource(const std::string& name) {
    for (const fs::path& p : test::oacmpMapSources())
        if (p.stem() == name) return p;
    ADD_FAILURE() << "no .map source named " << name;
    throw std::runtime_error("missing map source " + name);
}

class LightConformance : public ReferenceTest<MapCase> {};

TEST_P(LightConformance, OursMatchesTheReference) {
    const MapCase& mc = GetParam();
    const fs::path& reference = this->reference();
    const fs::path cache = test::dataCache();
    const fs::path gameBase = test::openArenaBase();
    const fs::path source = mapSource(mc.map);
    const fs::path work = test::tempDir();
    const fs::path fresh = mc.ownBsp ? ownFreshCompile(test::q3map2Exe(), gameBase, source, work / "fresh")
                                     : freshCompile(reference, gameBase, cache, source);

    const fs::path refBsp = stageFresh(fresh, work / "reference", mc.map);
    const fs::path ref2Bsp = stageFresh(fresh, work / "reference-threads1", mc.map);
    const fs::path ourBsp = stageFresh(fresh, work / "ours", mc.map);
    const ToolRun refRun = lightWithReference(reference, gameBase, refBsp, mc.options, 2);
    ASSERT_EQ(refRun.exitCode, 0) << refRun.output;
    const ToolRun ref2Run = lightWithReference(reference, gameBase, ref2Bsp, mc.options, 1);
    ASSERT_EQ(ref2Run.exitCode, 0) << ref2Run.output;
    const ToolRun ourRun = lightWithOurs(test::q3map2Exe(), gameBase, ourBsp, mc.options, 2);
    ASSERT_EQ(ourRun.exitCode, 0) << ourRun.output;

    const LitBsp refLit = loadLitBsp(refBsp);
    const LitBsp ref2Lit = loadLitBsp(ref2Bsp);
    const LitBsp ourLit = loadLitBsp(ourBsp);
    const ClassInputs classes = loadClassInputs(refLit.bsp, source, {gameBase}, "baseoa");
    const Comparison c = compareLitBsps(refLit, ourLit, &ref2Lit, classes);
    std::cout << toText(c, 20) << "wall: reference " << refRun.wallSeconds << " s, ours " << ourRun.wallSeconds
              << " s\n";

    const Limits& lim = mc.limits;
    const LightmapFigures& lm = c.lightmaps;
    ASSERT_GT(lm.referenceLit, 0);
    EXPECT_LE(std::abs(lm.oursLit - lm.referenceLit), lim.lightmappedCount * lm.referenceLit)
        << "lightmapped surfaces: ours " << lm.oursLit << ", reference " << lm.referenceLit;
    // Over the surfaces the reference's two runs agree on: its threads race on some surfaces, and
    // a limit must not follow that (the classes are counted the same way).
    ASSERT_GT(lm.repeatable, lm.referenceLit / 2) << "the two reference runs disagree on most surfaces";
    EXPECT_LE(std::abs(lm.repeatableRatio - 1), lim.lightmapRatio) << "lightmap total ratio " << lm.repeatableRatio;
    EXPECT_GE(lm.repeatableCorrelation, lim.lightmapCorrelation) << "per-surface correlation";
    for (const ClassFigures& k : lm.classes) {
        if (!k.measured || k.surfaces == 0) continue;
        const auto named = lim.classRatioOf.find(k.name);
        const double limit = named != lim.classRatioOf.end() ? named->second : lim.classRatio;
        EXPECT_LE(std::abs(k.ratio - 1), limit) << "class " << k.name << " ratio " << k.ratio;
    }

    const GridFigures& g = c.grid;
    ASSERT_TRUE(g.countsMatch) << "grid points: ours " << g.oursPoints << ", reference " << g.referencePoints;
    ASSERT_TRUE(g.masked);
    int placed = 0;  // points the reference wrote anything to (see gridPointPlaced)
    for (const bsp::GridPoint& p : refLit.bsp.lightGrid) placed += gridPointPlaced(p);
    EXPECT_GT(g.agreed.points, placed / 2) << "the two reference runs disagree on most grid points they placed";
    EXPECT_LE(std::abs(g.agreed.ambientRatio - 1), lim.gridAmbient) << "grid ambient ratio";
    EXPECT_LE(std::abs(g.agreed.directedRatio - 1), lim.gridDirected) << "grid directed ratio";
    EXPECT_GE(g.agreed.ambientCorrelation, lim.gridAmbientCorrelation) << "grid ambient correlation";
    EXPECT_GE(g.agreed.directedCorrelation, lim.gridDirectedCorrelation) << "grid directed correlation";
    EXPECT_GE(g.agreed.directionFraction, lim.gridDirection) << "grid directions within 15 degrees";

    const GridFigures oneThread = compareGrids(ref2Lit.bsp.lightGrid, ourLit.bsp.lightGrid, nullptr);
    EXPECT_GE(oneThread.all.ambientCorrelation, lim.gridOneThreadCorrelation) << "grid ambient, -threads 1";
    EXPECT_GE(oneThread.all.directedCorrelation, lim.gridOneThreadCorrelation) << "grid directed, -threads 1";

    if (c.vertexes.vertexes > 0) {
        EXPECT_LE(std::abs(c.vertexes.ratio - 1), lim.vertexRatio) << "vertex colours";
    }
}

INSTANTIATE_TEST_SUITE_P(Oacmp, LightConformance, ::testing::ValuesIn(cases()), caseName);

}  // namespace
}  // namespace q3::conformance
