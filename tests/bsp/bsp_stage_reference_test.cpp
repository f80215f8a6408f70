// The -bsp stage against q3map2 2.5.17n (plain -bsp, no -meta) on the 13 oacmp maps, by what
// players meet rather than by bytes: the contents at 20000 random points (at least 99.9 % equal),
// the drawn area of every shader (within 1 %), and the reference's own -vis and -light -fast
// accepting our BSP, .prt and .srf. Also: the same bytes with one and two threads, and the lumps
// that -noob, -globalflag, -snap, -skyfix, -rename and -maxarea change, and the -autocaulk file,
// equal to q3map2's.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <sstream>

#include <tbb/global_control.h>

#include "bsp_compare.h"
#include "bsp_reference.h"
#include "bsp_options.h"
#include "bsp_stage.h"
#include "file_io.h"
#include "log.h"
#include "option_parser.h"
#include "reference_fixture.h"
#include "test_data.h"

namespace q3::bspstage {
namespace {

namespace fs = std::filesystem;
using namespace q3::bspstage::test;

constexpr int kPoints = 20000;

// Runs the reference q3map2 stage `stageArgs` (e.g. "-vis -fast") on `bspPath`; returns its exit status.
int runReferenceStage(const fs::path& reference, const std::string& stageArgs, const fs::path& bspPath,
                      std::string& output) {
    return q3::test::runCommand(q3::test::shellQuote(reference) + " -threads 2 -game quake3 -fs_basepath " +
                                    q3::test::shellQuote(q3::test::openArenaBase()) + " -fs_basegame baseoa " +
                                    stageArgs + " " + q3::test::shellQuote(bspPath),
                                &output);
}

class BspStageReference : public conformance::ReferenceTest<fs::path> {};

TEST_P(BspStageReference, ContentsAndDrawnAreasMatchQ3map2) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const fs::path refDir = referenceCompile(reference(), mapSource, {}, false);
    const fs::path work = fs::temp_directory_path() / ("bsp-stage-ref-" + name + "-" + std::to_string(::getpid()));
    const bsp::Bsp ours = bsp::readBsp(ourCompile(mapSource, work));
    const bsp::Bsp theirs = bsp::readBsp(refDir / (name + ".bsp"));

    int same = 0;
    for (const Vec3& p : randomPoints(theirs, kPoints, 1234)) same += pointContents(ours, p) == pointContents(theirs, p);
    const double agreement = double(same) / kPoints;
    const AreaComparison areas = compareAreas(drawnAreaByShader(ours), drawnAreaByShader(theirs), 0.01);
    std::printf("%-10s contents %.3f %% of %d points  shaders within 1 %%: %d of %d  surfaces %zu / %zu\n", name.c_str(),
                100.0 * agreement, kPoints, areas.within, areas.shaders, ours.surfaces.size(), theirs.surfaces.size());
    for (const std::string& s : areas.outside) std::printf("    area differs: %s\n", s.c_str());
    EXPECT_GE(agreement, 0.999);
    EXPECT_EQ(areas.within, areas.shaders);
    fs::remove_all(work);
}

TEST_P(BspStageReference, ReferenceVisReadsOurPortalFile) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const fs::path work = fs::temp_directory_path() / ("bsp-stage-vis-" + name + "-" + std::to_string(::getpid()));
    const fs::path bspPath = ourCompile(mapSource, work);
    std::string output;
    const int status = runReferenceStage(reference(), "-vis -fast", bspPath, output);
    EXPECT_EQ(status, 0) << output.substr(0, 2000);
    const bsp::Bsp visible = bsp::readBsp(bspPath);
    EXPECT_FALSE(visible.visibility.empty()) << name << ": the reference wrote no visibility";
    fs::remove_all(work);
}

std::string mapName(const ::testing::TestParamInfo<fs::path>& info) { return info.param.stem().string(); }

INSTANTIATE_TEST_SUITE_P(Oacmp, BspStageReference, ::testing::ValuesIn(q3::test::oacmpMapSourcesForRegistration()),
                         mapName);

// The same bytes whatever the thread count (oacmpdm1, the oacmp map with models and fog).
TEST(BspStageDeterminism, SameOutputWithOneAndTwoThreads) {
    fs::path mapSource;
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == "oacmpdm1") mapSource = p;
    ASSERT_FALSE(mapSource.empty());
    std::string bsp[2], srf[2];
    for (int threads = 1; threads <= 2; ++threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const fs::path work = fs::temp_directory_path() / ("bsp-stage-threads-" + std::to_string(threads) + "-" +
                                                           std::to_string(::getpid()));
        const fs::path bspPath = ourCompile(mapSource, work);
        bsp[threads - 1] = readFileText(bspPath);
        srf[threads - 1] = readFileText(fs::path(bspPath).replace_extension(".srf"));
        fs::remove_all(work);
    }
    EXPECT_TRUE(bsp[0] == bsp[1]);
    EXPECT_TRUE(srf[0] == srf[1]);
}

// -bsp options against the reference's compile with the same options: the lumps each option
// changes must come out byte for byte as q3map2 writes them, and the drawn areas stay within 1 %.
struct OptionCase {
    std::string name;
    std::string map;
    std::string args;
    bool shaders = false, planes = false, brushes = false, leafSurfaces = false;
    bool shaderOnlySurfaces = false;  // -skyfix: the MST_FLARE records
};

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

std::vector<bsp::Surface> flareRecords(const bsp::Bsp& bsp) {
    std::vector<bsp::Surface> out;
    for (const bsp::Surface& s : bsp.surfaces)
        if (s.surfaceType == bsp::MST_FLARE) out.push_back(s);
    return out;
}

class BspStageOptions : public conformance::ReferenceTest<OptionCase> {};

TEST_P(BspStageOptions, ChangedLumpsEqualQ3map2s) {
    const OptionCase& c = GetParam();
    fs::path mapSource;
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == c.map) mapSource = p;
    ASSERT_FALSE(mapSource.empty()) << c.map;
    std::vector<std::string> args;
    std::istringstream words(c.args);
    for (std::string w; words >> w;) args.push_back(w);
    BspOptions options;
    cli::parseOptions(bspOptionTable(), args, cli::ParseContext{}, options);
    const fs::path refDir = referenceCompile(reference(), mapSource, c.args, false);
    const fs::path work = fs::temp_directory_path() / ("bsp-stage-opt-" + c.name + "-" + std::to_string(::getpid()));
    const bsp::Bsp ours = bsp::readBsp(ourCompile(mapSource, work, options));
    const bsp::Bsp theirs = bsp::readBsp(refDir / (c.map + ".bsp"));
    if (c.shaders) EXPECT_TRUE(sameBytes(ours.shaders, theirs.shaders));
    if (c.planes) EXPECT_TRUE(sameBytes(ours.planes, theirs.planes));
    if (c.brushes) {
        EXPECT_TRUE(sameBytes(ours.brushes, theirs.brushes));
        EXPECT_TRUE(sameBytes(ours.brushSides, theirs.brushSides));
    }
    if (c.leafSurfaces) EXPECT_TRUE(sameBytes(ours.leafSurfaces, theirs.leafSurfaces));
    if (c.shaderOnlySurfaces) {
        EXPECT_FALSE(flareRecords(theirs).empty());
        EXPECT_TRUE(sameBytes(flareRecords(ours), flareRecords(theirs)));
    }
    const AreaComparison areas = compareAreas(drawnAreaByShader(ours), drawnAreaByShader(theirs), 0.01);
    for (const std::string& s : areas.outside) std::printf("    area differs: %s\n", s.c_str());
    EXPECT_EQ(areas.within, areas.shaders);
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(
    Oacmp, BspStageOptions,
    ::testing::Values(
        OptionCase{"NoObGlobalFlags", "oacmpdm1", "-noob -globalflag slick -globalflag nodamage", true, false, true},
        OptionCase{"Snap", "oacmpdm4", "-snap 16", false, true, true},
        OptionCase{"SkyFix", "oacmpdm4", "-skyfix", true, false, false, true, true},
        OptionCase{"Rename", "oacmpdm1", "-rename", true, false, true},
        OptionCase{"MaxArea", "oacmpdm1", "-maxarea", true, true, true, true}),
    [](const ::testing::TestParamInfo<OptionCase>& info) { return info.param.name; });

// -autocaulk: the .caulk of every oacmp map equals q3map2's, and no BSP is written.
TEST_P(BspStageReference, AutocaulkFileEqualsQ3map2s) {
    const fs::path mapSource = GetParam();
    const std::string name = mapSource.stem().string();
    const fs::path refDir = referenceCompile(reference(), mapSource, "-autocaulk", false);
    const fs::path work = fs::temp_directory_path() / ("bsp-stage-caulk-" + name + "-" + std::to_string(::getpid()));
    BspOptions options;
    options.autocaulk = true;
    const fs::path bspPath = ourCompile(mapSource, work, options);
    EXPECT_FALSE(fs::exists(bspPath));
    EXPECT_FALSE(fs::exists(fs::path(bspPath).replace_extension(".prt")));
    EXPECT_EQ(readFileText(fs::path(bspPath).replace_extension(".caulk")), readFileText(refDir / (name + ".caulk")));
    fs::remove_all(work);
}

// The reference -light -fast lights our BSP with our .srf (one map: other runs take a minute).
class BspStageLight : public conformance::ReferenceTest<std::string> {};

TEST_P(BspStageLight, ReferenceLightAcceptsOurBspAndSrf) {
    fs::path mapSource;
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == GetParam()) mapSource = p;
    ASSERT_FALSE(mapSource.empty()) << GetParam();
    const fs::path work = fs::temp_directory_path() / ("bsp-stage-light-" + GetParam() + "-" + std::to_string(::getpid()));
    const fs::path bspPath = ourCompile(mapSource, work);
    std::string output;
    const int status = runReferenceStage(reference(), "-light -fast", bspPath, output);
    EXPECT_EQ(status, 0) << output.substr(0, 2000);
    EXPECT_NE(output.find(".srf"), std::string::npos) << "the reference did not read our .srf";
    const bsp::Bsp lit = bsp::readBsp(bspPath);
    EXPECT_FALSE(lit.lightmaps.empty());
    EXPECT_FALSE(lit.lightGrid.empty());
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, BspStageLight, ::testing::Values("oacmpdm1"));

}  // namespace
}  // namespace q3::bspstage
