// -bsp -meta against q3map2 2.5.17n on the oacmp maps: draw surface, vertex and index counts
// within 1 % and the T-junction vertices within 3 % on all 13, contents and drawn areas as players
// meet them; with -notjunc (so that the face vertices going in are the same) every meta surface of
// oacmpdm9 has q3map2's vertices and triangles; the reference -light reads our -meta BSP and .srf;
// the same bytes with one and two threads.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <regex>
#include <set>
#include <tuple>

#include <tbb/global_control.h>

#include "bsp_compare.h"
#include "bsp_reference.h"
#include "bsp_options.h"
#include "bsp_stage.h"
#include "file_io.h"
#include "log.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

BspOptions metaOptions() {
    BspOptions o;
    o.meta = true;
    return o;
}

int tjunctionVerts(const std::string& log) {
    static const std::regex line(R"(^\s*(\d+) verts added for T-junctions)", std::regex::multiline);
    int total = 0;
    for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator(); ++it)
        total += std::stoi((*it)[1]);
    return total;
}

struct Counts {
    size_t surfaces = 0, verts = 0, indexes = 0;
};

Counts counts(const bsp::Bsp& b) {
    Counts c{b.surfaces.size(), 0, 0};
    for (const bsp::Surface& s : b.surfaces) {
        c.verts += size_t(s.numVerts);
        c.indexes += size_t(s.numIndexes);
    }
    return c;
}

double relative(size_t ours, size_t theirs) { return theirs ? std::abs(double(ours) - double(theirs)) / double(theirs) : 0; }

fs::path sourceNamed(const std::string& name) {
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == name) return p;
    return {};
}

fs::path scratch(const std::string& what, const std::string& name) {
    return fs::temp_directory_path() / ("bsp-meta-" + what + "-" + name + "-" + std::to_string(::getpid()));
}

class BspMetaReference : public conformance::ReferenceTest<fs::path> {};

TEST_P(BspMetaReference, CountsContentsAndAreasMatchQ3map2) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const fs::path refDir = referenceCompile(reference(), mapSource, {}, true);
    const fs::path work = scratch("counts", name);
    std::string log;
    const bsp::Bsp ours = bsp::readBsp(ourCompile(mapSource, work, metaOptions(), &log));
    const bsp::Bsp theirs = bsp::readBsp(refDir / (name + ".bsp"));
    const Counts o = counts(ours), t = counts(theirs);
    const int tjOurs = tjunctionVerts(log), tjTheirs = tjunctionVerts(readFileText(refDir / (name + ".log")));
    std::printf("%-10s surfaces %zu / %zu  verts %zu / %zu  indexes %zu / %zu  T-junction verts %d / %d\n",
                name.c_str(), o.surfaces, t.surfaces, o.verts, t.verts, o.indexes, t.indexes, tjOurs, tjTheirs);
    EXPECT_LE(relative(o.surfaces, t.surfaces), 0.01);
    EXPECT_LE(relative(o.verts, t.verts), 0.01);
    EXPECT_LE(relative(o.indexes, t.indexes), 0.01);
    EXPECT_LE(relative(size_t(tjOurs), size_t(tjTheirs)), 0.03);
    for (const bsp::Surface& s : ours.surfaces) {
        if (s.surfaceType == bsp::MST_PLANAR) EXPECT_LE(s.numVerts, 64);
        EXPECT_LE(s.numIndexes, 6000);
    }

    int same = 0;
    for (const Vec3& p : randomPoints(theirs, 5000, 99)) same += pointContents(ours, p) == pointContents(theirs, p);
    EXPECT_GE(same, 4995);
    const AreaComparison areas = compareAreas(drawnAreaByShader(ours), drawnAreaByShader(theirs), 0.01);
    for (const std::string& s : areas.outside) std::printf("    area differs: %s\n", s.c_str());
    EXPECT_EQ(areas.within, areas.shaders);
    fs::remove_all(work);
}

std::string mapName(const ::testing::TestParamInfo<fs::path>& info) { return info.param.stem().string(); }

INSTANTIATE_TEST_SUITE_P(Oacmp, BspMetaReference, ::testing::ValuesIn(q3::test::oacmpMapSourcesForRegistration()),
                         mapName);

// A surface as geometry: shader, type, its corners (rounded to 1/1000) and its triangles as corner sets.
using Corner = std::array<long, 3>;
using Geometry = std::tuple<std::string, int, std::vector<Corner>, std::set<std::array<Corner, 3>>>;

std::multiset<Geometry> geometry(const bsp::Bsp& b) {
    std::multiset<Geometry> out;
    for (const bsp::Surface& s : b.surfaces) {
        auto corner = [&](int i) {
            const bsp::DrawVert& v = b.drawVerts[size_t(s.firstVert + i)];
            return Corner{std::lround(v.xyz[0] * 1000), std::lround(v.xyz[1] * 1000), std::lround(v.xyz[2] * 1000)};
        };
        std::vector<Corner> corners;
        for (int i = 0; i < s.numVerts; ++i) corners.push_back(corner(i));
        std::sort(corners.begin(), corners.end());
        std::set<std::array<Corner, 3>> triangles;
        for (int i = 0; i + 2 < s.numIndexes; i += 3) {
            std::array<Corner, 3> t;
            for (int k = 0; k < 3; ++k) t[size_t(k)] = corner(b.drawIndexes[size_t(s.firstIndex + i + k)]);
            std::sort(t.begin(), t.end());
            triangles.insert(t);
        }
        out.insert({b.shaders[size_t(s.shaderNum)].name, s.surfaceType, corners, triangles});
    }
    return out;
}

class BspMetaMerge : public conformance::ReferenceTest<std::string> {};

TEST_P(BspMetaMerge, WithTheSameFacesEveryMergedSurfaceIsQ3map2s) {
    const fs::path mapSource = sourceNamed(GetParam());
    ASSERT_FALSE(mapSource.empty()) << GetParam();
    const fs::path refDir = referenceCompile(reference(), mapSource, "-notjunc", true);
    const fs::path work = scratch("merge", GetParam());
    BspOptions options = metaOptions();
    options.noTJunc = true;
    const bsp::Bsp ours = bsp::readBsp(ourCompile(mapSource, work, options));
    const bsp::Bsp theirs = bsp::readBsp(refDir / (GetParam() + ".bsp"));
    const std::multiset<Geometry> a = geometry(ours), b = geometry(theirs);
    std::vector<Geometry> common;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
    std::printf("%s -notjunc: %zu of %zu surfaces with q3map2's geometry\n", GetParam().c_str(), common.size(), b.size());
    EXPECT_EQ(common.size(), b.size());
    EXPECT_EQ(a.size(), b.size());
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, BspMetaMerge, ::testing::Values("oacmpdm9"));

// The reference -light -fast reads our -meta BSP and .srf (a small map: the large ones take minutes).
class BspMetaLight : public conformance::ReferenceTest<std::string> {};

TEST_P(BspMetaLight, ReferenceLightAcceptsOurMetaBspAndSrf) {
    const fs::path mapSource = sourceNamed(GetParam());
    ASSERT_FALSE(mapSource.empty()) << GetParam();
    const fs::path work = scratch("light", GetParam());
    const fs::path bspPath = ourCompile(mapSource, work, metaOptions());
    std::string output;
    const int status = q3::test::runCommand(
        q3::test::shellQuote(reference()) + " -threads 2 -game quake3 -fs_basepath " +
            q3::test::shellQuote(q3::test::openArenaBase()) + " -fs_basegame baseoa -light -fast " +
            q3::test::shellQuote(bspPath),
        &output);
    EXPECT_EQ(status, 0) << output.substr(0, 2000);
    EXPECT_NE(output.find(".srf"), std::string::npos) << "the reference did not read our .srf";
    const bsp::Bsp lit = bsp::readBsp(bspPath);
    EXPECT_FALSE(lit.lightmaps.empty());
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, BspMetaLight, ::testing::Values("oacmpdm2"));

TEST(BspMetaDeterminism, SameOutputWithOneAndTwoThreads) {
    const fs::path mapSource = sourceNamed("oacmpdm1");
    ASSERT_FALSE(mapSource.empty());
    std::string bsp[2], srf[2];
    for (int threads = 1; threads <= 2; ++threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const fs::path work = scratch("threads-" + std::to_string(threads), "oacmpdm1");
        const fs::path bspPath = ourCompile(mapSource, work, metaOptions());
        bsp[threads - 1] = readFileText(bspPath);
        srf[threads - 1] = readFileText(fs::path(bspPath).replace_extension(".srf"));
        fs::remove_all(work);
    }
    EXPECT_TRUE(bsp[0] == bsp[1]);
    EXPECT_TRUE(srf[0] == srf[1]);
}

}  // namespace
}  // namespace q3::bspstage
