// Our world structure against q3map2 2.5.17n on the oacmp maps: clusters, portals and solid faces
// from the reference's .prt, the leaf count of its final face tree from its -v log, and the .prt
// text itself.
//
// The reference compiles are cached (bsp_reference.h), so a rerun does not compile again.
//
// No tolerance: the counts must be equal and the .prt text byte-identical (it is on all 13 maps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "bsp_brushes.h"
#include "bsp_reference.h"
#include "file_io.h"
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
    std::string portalFile;
};

StructureCounts referenceCounts(const fs::path& folder, const std::string& name) {
    StructureCounts c;
    std::ifstream prt(folder / (name + ".prt"), std::ios::binary);
    c.portalFile.assign(std::istreambuf_iterator<char>(prt), std::istreambuf_iterator<char>());
    std::istringstream header(c.portalFile);
    std::string magic;
    header >> magic >> c.clusters >> c.portals >> c.solidFaces;
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

StructureCounts ourCounts(const fs::path& mapSource, const WorldStructureOptions& options = {}) {
    Log log(false);
    const map::MapFile file = map::loadMap(mapSource);
    LoadedMap map = loadMapForBsp(file, openArenaShaders(), {}, log);
    const WorldStructure world = buildWorldStructure(map, options, log);
    EXPECT_FALSE(world.leaked) << mapSource;
    return {world.clusters.clusters, world.clusters.portals, world.clusters.solidFaces, world.second.faceBsp.leafs,
            world.portalFile};
}

// Lines that differ at the same position, and the number of lines of `reference`.
std::pair<int, int> differingLines(const std::string& ours, const std::string& reference) {
    std::istringstream a(ours), b(reference);
    int differ = 0, total = 0;
    for (std::string la, lb; std::getline(b, lb);) {
        ++total;
        if (!std::getline(a, la) || la != lb) ++differ;
    }
    return {differ, total};
}

class BspReferenceCounts : public conformance::ReferenceTest<fs::path> {};

TEST_P(BspReferenceCounts, PortalFileAndLeafCountsMatchQ3map2) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const StructureCounts ref = referenceCounts(referenceCompile(reference(), mapSource), name);
    ASSERT_GT(ref.clusters, 0) << "no reference .prt for " << name;
    ASSERT_GT(ref.leafs, 0) << "no leaf count in the reference log for " << name;
    const StructureCounts ours = ourCounts(mapSource);
    const auto [differ, lines] = differingLines(ours.portalFile, ref.portalFile);
    std::printf("%-10s clusters %5d / %5d  portals %5d / %5d  solid faces %5d / %5d  leafs %5d / %5d  (ours / q3map2)  "
                ".prt: %s\n",
                name.c_str(), ours.clusters, ref.clusters, ours.portals, ref.portals, ours.solidFaces, ref.solidFaces,
                ours.leafs, ref.leafs,
                differ ? (std::to_string(differ) + " of " + std::to_string(lines) + " lines differ").c_str() : "identical");
    EXPECT_EQ(ours.clusters, ref.clusters);
    EXPECT_EQ(ours.portals, ref.portals);
    EXPECT_EQ(ours.solidFaces, ref.solidFaces);
    EXPECT_EQ(ours.leafs, ref.leafs);
    EXPECT_EQ(differ, 0) << "of " << lines << " lines";
}

std::string mapName(const ::testing::TestParamInfo<fs::path>& info) { return info.param.stem().string(); }

INSTANTIATE_TEST_SUITE_P(Oacmp, BspReferenceCounts, ::testing::ValuesIn(q3::test::oacmpMapSourcesForRegistration()), mapName);

// -altsplit on two maps: the .prt must be byte-identical.
class AlternateSplit : public conformance::ReferenceTest<std::string> {};

TEST_P(AlternateSplit, PortalFileMatchesQ3map2) {
    fs::path mapSource;
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == GetParam()) mapSource = p;
    ASSERT_FALSE(mapSource.empty()) << GetParam();
    const StructureCounts ref = referenceCounts(referenceCompile(reference(), mapSource, "-altsplit"), GetParam());
    WorldStructureOptions options;
    options.alternateSplit = true;
    const StructureCounts ours = ourCounts(mapSource, options);
    std::printf("%-10s -altsplit clusters %5d / %5d  portals %5d / %5d  (ours / q3map2)\n", GetParam().c_str(),
                ours.clusters, ref.clusters, ours.portals, ref.portals);
    EXPECT_EQ(ours.portalFile, ref.portalFile);
    // The alternative score builds another tree than the default one.
    EXPECT_NE(ours.portalFile, ourCounts(mapSource).portalFile);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, AlternateSplit, ::testing::Values("oacmpdm1", "oacmpdm7"));

// oacmpdm7 without the first brush of its worldspawn leaks: the line files must be identical.
class LeakLine : public conformance::ReferenceTest<int> {};

TEST_P(LeakLine, LineFileMatchesQ3map2) {
    fs::path source;
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == "oacmpdm7") source = p;
    ASSERT_FALSE(source.empty());
    std::ifstream in(source, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The editor's comments mark the brushes: cut "// brush 0" of "// entity 0" up to "// brush 1".
    const size_t worldspawn = text.find("// entity 0");
    const size_t first = text.find("// brush 0", worldspawn);
    size_t second = text.find("// brush 1", first);
    while (second != std::string::npos && std::isdigit(static_cast<unsigned char>(text[second + 10])))
        second = text.find("// brush 1", second + 1);  // not "// brush 10"
    ASSERT_NE(second, std::string::npos);
    text.erase(first, second - first);
    const fs::path leaky = q3::test::tempDir() / "oacmpdm7leak.map";
    writeFileAtomic(leaky, text);

    const fs::path folder = referenceCompile(reference(), leaky);
    std::ifstream lin(folder / "oacmpdm7leak.lin", std::ios::binary);
    const std::string referenceLine((std::istreambuf_iterator<char>(lin)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(referenceLine.empty()) << "q3map2 wrote no line file";
    EXPECT_FALSE(fs::exists(folder / "oacmpdm7leak.prt"));

    Log log(false);
    const map::MapFile file = map::loadMap(leaky);
    LoadedMap map = loadMapForBsp(file, openArenaShaders(), {}, log);
    const WorldStructure world = buildWorldStructure(map, {}, log);
    EXPECT_EQ(world.flood, FloodResult::Leaked);
    EXPECT_TRUE(world.portalFile.empty());
    EXPECT_EQ(world.leakLine, referenceLine);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, LeakLine, ::testing::Values(0));

TEST(BspReferenceCounts, AllOacmpMapsAreThere) { EXPECT_EQ(q3::test::oacmpMapSources().size(), 13u); }

}  // namespace
}  // namespace q3::bspstage
