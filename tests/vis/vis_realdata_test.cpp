// -vis on real maps compiled by the reference q3map2 (-bsp -meta): our -fast against its -fast
// byte for byte, our full vis against its full vis (no more than 1 % more visible clusters),
// a conservative PVS by an independent segment test, identical bytes at 1 and 2 threads, and the
// stage's file handling (the .prt, bad input, other lumps untouched).
#include "bspfile.h"
#include "cluster_vis.h"
#include "file_io.h"
#include "reference_fixture.h"
#include "segment_clearance.h"
#include "test_data.h"
#include "vis_reference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

namespace q3::vis::test {
namespace {
namespace fs = std::filesystem;

using Fixture = conformance::ReferenceTest<std::string>;

std::string paramName(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

// Worldspawn without the keys each compile stamps.
std::vector<bsp::Entity> entitiesWithoutStamp(const bsp::Bsp& bsp) {
    std::vector<bsp::Entity> entities = bsp::parseEntities(bsp.entities, "bsp");
    entities.at(0).erase("_q3map2_cmdline");
    entities.at(0).erase("_q3map2_version");
    return entities;
}

// Every lump but the entities and the visibility is byte for byte the input's; the entities
// differ only in the recorded command line.
void expectOnlyVisChanged(const fs::path& input, const fs::path& output) {
    const bsp::Bsp a = bsp::readBsp(input), b = bsp::readBsp(output);
    for (int lump = 1; lump < bsp::kMaxLumps; ++lump) {
        if (lump == bsp::LUMP_VISIBILITY) continue;
        EXPECT_TRUE(bsp::lumpView(a, lump).size() == bsp::lumpView(b, lump).size() &&
                    std::equal(bsp::lumpView(a, lump).begin(), bsp::lumpView(a, lump).end(), bsp::lumpView(b, lump).begin()))
            << "lump " << lump << " changed";
    }
    EXPECT_EQ(bsp::unparseEntities(entitiesWithoutStamp(a)), bsp::unparseEntities(entitiesWithoutStamp(b)));
    EXPECT_NE(bsp::parseEntities(b.entities, "out")[0].value("_q3map2_cmdline").find("-vis"), std::string::npos);
}

double meanVisibleFraction(const std::vector<uint8_t>& lump) {
    const VisSummary s = summarizeVisibility(lump);
    return s.clusters ? s.averageVisible / s.clusters : 0;
}

struct ConservativeCheck {
    int clearPairs = 0;
    int hidden = 0;  // clear pairs whose clusters do not see each other
    std::string firstHidden;
};

// Random points in empty space; pairs whose segment stays 1 unit away from every solid brush
// must see each other's cluster.
ConservativeCheck checkConservative(const bsp::Bsp& bsp, const std::vector<uint8_t>& lump, int points, int pairsPerPoint) {
    const SolidWorld world(bsp);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> ux(world.mins.x, world.maxs.x), uy(world.mins.y, world.maxs.y),
        uz(world.mins.z, world.maxs.z);
    std::vector<std::pair<Vec3, int>> samples;
    for (int attempt = 0; attempt < points * 200 && static_cast<int>(samples.size()) < points; ++attempt) {
        const Vec3 p{ux(rng), uy(rng), uz(rng)};
        const int cluster = world.clusterAt(p);
        if (cluster >= 0 && world.segmentClear(p, p, 1.0f)) samples.push_back({p, cluster});
    }
    ConservativeCheck check;
    std::uniform_int_distribution<size_t> pick(0, samples.size() - 1);
    for (size_t i = 0; i < samples.size(); ++i)
        for (int k = 0; k < pairsPerPoint; ++k) {
            const auto& [a, ca] = samples[i];
            const auto& [b, cb] = samples[pick(rng)];
            if (ca == cb || !world.segmentClear(a, b, 1.0f)) continue;
            ++check.clearPairs;
            if (lumpSees(lump, ca, cb)) continue;
            if (check.hidden++ == 0) {
                char buf[200];
                std::snprintf(buf, sizeof buf, "(%.1f %.1f %.1f) in cluster %d to (%.1f %.1f %.1f) in cluster %d", a.x,
                              a.y, a.z, ca, b.x, b.y, b.z, cb);
                check.firstHidden = buf;
            }
        }
    return check;
}

void expectConservative(const fs::path& bspPath, int points = 3000, int pairsPerPoint = 12) {
    const bsp::Bsp bsp = bsp::readBsp(bspPath);
    const ConservativeCheck check = checkConservative(bsp, bsp.visibility, points, pairsPerPoint);
    EXPECT_GT(check.clearPairs, 1000) << "too few clear pairs to say anything";
    EXPECT_EQ(check.hidden, 0) << check.hidden << " of " << check.clearPairs << " clear pairs hidden, first "
                               << check.firstHidden;
    std::printf("[ conservative ] %s: %d clear pairs, %d hidden\n", bspPath.filename().c_str(), check.clearPairs, check.hidden);
    // The check itself can fail: a PVS where each cluster sees only itself hides most clear pairs.
    std::vector<uint8_t> selfOnly(bsp.visibility.size(), 0);
    std::copy_n(bsp.visibility.begin(), 8, selfOnly.begin());
    const VisSummary s = summarizeVisibility(bsp.visibility);
    const size_t rowBytes = (bsp.visibility.size() - 8) / static_cast<size_t>(std::max(1, s.clusters));
    for (int c = 0; c < s.clusters; ++c) selfOnly[8 + static_cast<size_t>(c) * rowBytes + static_cast<size_t>(c >> 3)] |= 1u << (c & 7);
    EXPECT_GT(checkConservative(bsp, selfOnly, points / 4, pairsPerPoint).hidden, 0);
}

// -vis -fast: the same bytes as the reference's -fast ---------------------------------------------
class VisFast : public Fixture {};

TEST_P(VisFast, MatchesReferenceByteForByteAndChangesNothingElse) {
    const VisReference ref = visReference(reference(), GetParam(), false);
    const fs::path bsp = stageVisInputs(ref, q3::test::tempDir());
    std::string log;
    ASSERT_EQ(runOurVis(bsp, "-fast -saveprt", 2, &log), 0) << log;
    const bsp::Bsp ours = bsp::readBsp(bsp), theirs = bsp::readBsp(ref.fastBsp);
    EXPECT_EQ(ours.visibility, theirs.visibility);
    expectOnlyVisChanged(ref.bsp, bsp);
    EXPECT_TRUE(fs::exists(fs::path(bsp).replace_extension(".prt"))) << "-saveprt keeps the portal file";
}

INSTANTIATE_TEST_SUITE_P(Maps, VisFast, ::testing::Values("oacmpdm1", "oacmpdm5", "oacmpctf2"), paramName);

// Full vis: within 1 % of the reference, conservative, the same bytes at any thread count ---------
class VisFull : public Fixture {};

TEST_P(VisFull, WithinOnePercentOfReferenceConservativeAndThreadIndependent) {
    const VisReference ref = visReference(reference(), GetParam(), true);
    const fs::path temp = q3::test::tempDir();  // emptied at each call
    const fs::path two = stageVisInputs(ref, temp / "two");
    const fs::path one = stageVisInputs(ref, temp / "one");
    std::string log;
    ASSERT_EQ(runOurVis(two, "", 2, &log), 0) << log;
    ASSERT_EQ(runOurVis(one, "", 1, &log), 0) << log;
    EXPECT_TRUE(readFileBytes(one) == readFileBytes(two)) << "-threads 1 and -threads 2 differ";
    EXPECT_FALSE(fs::exists(fs::path(two).replace_extension(".prt"))) << "without -saveprt the .prt is deleted";

    const bsp::Bsp ours = bsp::readBsp(two), theirs = bsp::readBsp(ref.fullBsp);
    const double ourFraction = meanVisibleFraction(ours.visibility);
    const double theirFraction = meanVisibleFraction(theirs.visibility);
    std::printf("[ visible    ] %s: ours %.3f %%, reference %.3f %% of clusters\n", GetParam().c_str(),
                100 * ourFraction, 100 * theirFraction);
    EXPECT_LE(ourFraction, theirFraction * 1.01);
    EXPECT_LE(ourFraction, meanVisibleFraction(bsp::readBsp(ref.fastBsp).visibility));
    expectOnlyVisChanged(ref.bsp, two);
    // Q3MAP_VIS_SAMPLE_POINTS samples more (or fewer) points by hand; the suite takes 3000. At
    // 30000, oacmpdm5 shows 12 pairs q3map2's full vis hides as well (6 even its -fast flood):
    // their segments cross a slab 0.125 units thick at y 456 where the .prt has solid faces on
    // both sides and no portal, though no brush of the BSP lies there.
    const char* points = std::getenv("Q3MAP_VIS_SAMPLE_POINTS");
    expectConservative(two, points ? std::max(100, std::atoi(points)) : 3000);
}

// The suite samples four cheap maps, one of them open (oacmpdm8 sees three quarters of itself);
// Q3MAP_VIS_FULL_MAPS=oacmpdm9,oacmpdm10 (or "all") adds others by hand. The reference's full vis
// of the largest ones takes from minutes to most of an hour, once.
std::vector<std::string> fullVisMaps() {
    std::vector<std::string> maps{"oacmpdm1", "oacmpdm5", "oacmpdm8", "oacmpctf1"};
    const char* env = std::getenv("Q3MAP_VIS_FULL_MAPS");
    std::string extra = env ? env : "";
    if (extra == "all") {
        extra.clear();
        for (const fs::path& source : q3::test::oacmpMapSourcesForRegistration()) extra += source.stem().string() + ",";
    }
    for (size_t start = 0; start < extra.size();) {
        const size_t end = std::min(extra.find(',', start), extra.size());
        const std::string name = extra.substr(start, end - start);
        if (!name.empty() && std::find(maps.begin(), maps.end(), name) == maps.end()) maps.push_back(name);
        start = end + 1;
    }
    return maps;
}

INSTANTIATE_TEST_SUITE_P(Maps, VisFull, ::testing::ValuesIn(fullVisMaps()), paramName);

// The number before `label` on the line that ends with it ("   161 leaves merged"), or -1.
int countBefore(const std::string& log, const std::string& label) {
    const size_t at = log.find(" " + label + "\n");
    if (at == std::string::npos) return -1;
    const size_t start = log.rfind('\n', at);
    return std::stoi(log.substr(start == std::string::npos ? 0 : start + 1, at - (start == std::string::npos ? 0 : start + 1)));
}

// The other flow and merge options on a small map: each runs, merges exactly what q3map2 merges,
// stays conservative, no looser than the fast vis and within 1 % of q3map2 with the same option.
class VisOptions : public Fixture {};

TEST_P(VisOptions, MatchReferenceMergesConservativeWithinOnePercent) {
    const VisReference ref = visReference(reference(), "oacmpdm1", false);
    const fs::path theirs = referenceVisWith(reference(), ref, GetParam());
    const fs::path bsp = stageVisInputs(ref, q3::test::tempDir());
    std::string log;
    ASSERT_EQ(runOurVis(bsp, GetParam() + " -saveprt", 2, &log), 0) << log;
    const std::string theirLog = readFileText(fs::path(theirs).replace_extension(".log"));
    for (const char* label : {"leaves merged", "portals merged", "hint portals merged", "active portals", "hint portals"})
        EXPECT_EQ(countBefore(log, label), countBefore(theirLog, label)) << label;
    const double ourFraction = meanVisibleFraction(bsp::readBsp(bsp).visibility);
    const double theirFraction = meanVisibleFraction(bsp::readBsp(theirs).visibility);
    std::printf("[ visible    ] oacmpdm1 %s: ours %.3f %%, reference %.3f %% of clusters\n", GetParam().c_str(),
                100 * ourFraction, 100 * theirFraction);
    EXPECT_LE(ourFraction, theirFraction * 1.01);
    EXPECT_LE(ourFraction, meanVisibleFraction(bsp::readBsp(ref.fastBsp).visibility));
    expectConservative(bsp, 2000, 10);
}

INSTANTIATE_TEST_SUITE_P(Options, VisOptions,
                         ::testing::Values("-nopassage", "-passageOnly", "-nosort", "-merge", "-mergeportals", "-hint"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param.substr(1); });

// File handling ------------------------------------------------------------------------------------
class VisFiles : public Fixture {};

// A broken or mismatched .prt fails with one line naming it, and the BSP stays as it was.
TEST_P(VisFiles, BadPortalFileLeavesBspUntouched) {
    const VisReference ref = visReference(reference(), "oacmpdm1", false);
    const fs::path bsp = stageVisInputs(ref, q3::test::tempDir());
    const fs::path prt = fs::path(bsp).replace_extension(".prt");
    std::string text = readFileText(prt);
    const std::string kind = GetParam();
    std::string expected;
    if (kind == "truncated") {
        text.resize(text.size() / 2);
        expected = "file ends";
    } else if (kind == "header") {
        text.replace(0, 4, "PRT2");
        expected = "not a portal file";
    } else if (kind == "clusters") {
        const size_t end = text.find('\n', 5);
        text.replace(5, end - 5, std::to_string(std::stoi(text.substr(5, end - 5)) + 1));
        expected = "clusters, but the leafs of";
    }
    writeFileAtomic(prt, text);
    const std::vector<uint8_t> before = readFileBytes(bsp);
    std::string log;
    EXPECT_EQ(runOurVis(bsp, "", 2, &log), 1) << log;
    EXPECT_NE(log.find("ERROR: " + prt.string()), std::string::npos) << log;
    EXPECT_NE(log.find(expected), std::string::npos) << log;
    EXPECT_TRUE(readFileBytes(bsp) == before);
    EXPECT_TRUE(fs::exists(prt));
}

INSTANTIATE_TEST_SUITE_P(Kinds, VisFiles, ::testing::Values("truncated", "header", "clusters"), paramName);

class VisNoPortals : public Fixture {};

TEST_P(VisNoPortals, LeavesBspUntouched) {
    const VisReference ref = visReference(reference(), "oacmpdm1", false);
    const fs::path bsp = stageVisInputs(ref, q3::test::tempDir());
    const fs::path prt = fs::path(bsp).replace_extension(".prt");
    const std::string text = readFileText(prt);
    writeFileAtomic(prt, "PRT1\n" + text.substr(5, text.find('\n', 5) - 5) + "\n0\n0\n");
    const std::vector<uint8_t> before = readFileBytes(bsp);
    std::string log;
    EXPECT_EQ(runOurVis(bsp, "", 2, &log), 0) << log;
    EXPECT_NE(log.find("No portals means no vis, exiting."), std::string::npos) << log;
    EXPECT_TRUE(readFileBytes(bsp) == before);
}

INSTANTIATE_TEST_SUITE_P(Map, VisNoPortals, ::testing::Values("oacmpdm1"), paramName);

}  // namespace
}  // namespace q3::vis::test
