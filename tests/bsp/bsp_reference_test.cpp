// Our world structure against q3map2 2.5.17n on the oacmp maps: clusters, portals and solid faces
// from the reference's .prt, and the leaf count of its final face tree from its -v log.
//
// The reference compiles are cached (bsp_reference.h), so a rerun does not compile again.
//
// Tolerance: each count may differ by at most max(1, 0.2 %). q3map2 clips portals in 32-bit floats
// and we clip in doubles, so a portal right at the "tiny" limit can survive on one side only; every
// other difference is a bug.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "bsp_brushes.h"
#include "bsp_reference.h"
#include "log.h"
#include "map_file.h"
#include "reference_fixture.h"
#include "test_data.h"
#include "world_structure.h"

namespace q3::bspstage {
namespace {

using test::openArenaShaders;
using test::referenceCompile;

namespace fs = std::filesystem;

struct StructureCounts {
    int clusters = -1;
    int portals = -1;
    int solidFaces = -1;
    int leafs = -1;
};

StructureCounts referenceCounts(const fs::path& folder, const std::string& name) {
    StructureCounts c;
    std::ifstream prt(folder / (name + ".prt"));
    std::string magic;
    prt >> magic >> c.clusters >> c.portals >> c.solidFaces;
    // The last "--- FaceBSP ---" block is the visible-face tree: its "N leafs" line.
    std::ifstream log(folder / (name + ".log"));
    bool inFaceBsp = false;
    for (std::string line; std::getline(log, line);) {
        if (line.find("--- FaceBSP ---") != std::string::npos) inFaceBsp = true;
        int value = 0;
        char word[32] = {};
        if (inFaceBsp && std::sscanf(line.c_str(), "%d %31s", &value, word) == 2 && std::string(word) == "leafs") {
            c.leafs = value;
            inFaceBsp = false;
        }
    }
    return c;
}

StructureCounts ourCounts(const fs::path& mapSource) {
    Log log(false);
    const map::MapFile file = map::loadMap(mapSource);
    LoadedMap map = loadMapForBsp(file, openArenaShaders(), {}, log);
    const WorldStructure world = buildWorldStructure(map, {}, log);
    EXPECT_FALSE(world.leaked) << mapSource;
    return {world.clusters.clusters, world.clusters.portals, world.clusters.solidFaces, world.second.faceBsp.leafs};
}

bool withinTolerance(int ours, int reference) {
    const int allowed = std::max(1, reference / 500);
    return std::abs(ours - reference) <= allowed;
}

class BspReferenceCounts : public conformance::ReferenceTest<fs::path> {};

TEST_P(BspReferenceCounts, PortalFileAndLeafCountsMatchQ3map2) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const StructureCounts ref = referenceCounts(referenceCompile(reference(), mapSource), name);
    ASSERT_GT(ref.clusters, 0) << "no reference .prt for " << name;
    ASSERT_GT(ref.leafs, 0) << "no leaf count in the reference log for " << name;
    const StructureCounts ours = ourCounts(mapSource);
    std::printf("%-10s clusters %5d / %5d  portals %5d / %5d  solid faces %5d / %5d  leafs %5d / %5d  (ours / q3map2)\n",
                name.c_str(), ours.clusters, ref.clusters, ours.portals, ref.portals, ours.solidFaces, ref.solidFaces,
                ours.leafs, ref.leafs);
    EXPECT_PRED2(withinTolerance, ours.clusters, ref.clusters) << "clusters";
    EXPECT_PRED2(withinTolerance, ours.portals, ref.portals) << "portals";
    EXPECT_PRED2(withinTolerance, ours.solidFaces, ref.solidFaces) << "solid faces";
    EXPECT_PRED2(withinTolerance, ours.leafs, ref.leafs) << "leafs";
}

std::string mapName(const ::testing::TestParamInfo<fs::path>& info) { return info.param.stem().string(); }

INSTANTIATE_TEST_SUITE_P(Oacmp, BspReferenceCounts, ::testing::ValuesIn(q3::test::oacmpMapSourcesForRegistration()), mapName);

TEST(BspReferenceCounts, AllOacmpMapsAreThere) { EXPECT_EQ(q3::test::oacmpMapSources().size(), 13u); }

}  // namespace
}  // namespace q3::bspstage
