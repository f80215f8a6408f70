// The .prt reader: q3map2's format and quirks, and one clear error per kind of bad input.
#include "portal_file.h"
#include "vis_graph.h"

#include <gtest/gtest.h>

#include <string>

namespace q3::vis {
namespace {

const char* const kTwoClusters =
    "PRT1\n2\n1\n1\n"
    "4 0 1 1 (0 0 0 ) (0 10 0 ) (0 10 10 ) (0 0 10 ) \n"
    "3 1 (5 0 0 ) (5 10 0 ) (5 10 10 ) \n";

std::string errorOf(const std::string& text) {
    try {
        parsePortalFile(text, "maps/x.prt");
    } catch (const PortalFileError& e) {
        return e.what();
    }
    return "";
}

TEST(PortalFile, ReadsHeaderPortalsAndFaces) {
    const PortalFile f = parsePortalFile(kTwoClusters, "x.prt");
    EXPECT_EQ(f.clusterCount, 2);
    ASSERT_EQ(f.portals.size(), 1u);
    EXPECT_EQ(f.portals[0].clusters[0], 0);
    EXPECT_EQ(f.portals[0].clusters[1], 1);
    EXPECT_EQ(f.portals[0].flags, kPortalFlagHint);
    ASSERT_EQ(f.portals[0].points.size(), 4u);
    EXPECT_EQ(f.portals[0].points[2], (Vec3{0, 10, 10}));
    ASSERT_EQ(f.faces.size(), 1u);
    EXPECT_EQ(f.faces[0].cluster, 1);
    EXPECT_EQ(f.faces[0].points[0], (Vec3{5, 0, 0}));
}

TEST(PortalFile, ReadsNumbersAsScanfDoes) {
    // %i takes hexadecimal and octal; %f takes exponents; any white space separates.
    const PortalFile f = parsePortalFile("PRT1 0x2 01 0\n3 0 1 0 (1e1 0 0 )(0 2.5 0 ) ( 0 0 -3 )", "x.prt");
    EXPECT_EQ(f.clusterCount, 2);
    ASSERT_EQ(f.portals.size(), 1u);
    EXPECT_EQ(f.portals[0].points[0].x, 10.0f);
    EXPECT_EQ(f.portals[0].points[2].z, -3.0f);
}

TEST(PortalFile, EachFilePortalBecomesTwoWithTheHintQuirk) {
    const PortalFile f = parsePortalFile(kTwoClusters, "x.prt");
    for (bool hintSwitch : {false, true}) {
        const VisGraph g = buildVisGraph(f, hintSwitch);
        ASSERT_EQ(g.portals.size(), 2u);
        // Portal 0 lives in cluster 0 and leads into 1, its normal pointing into cluster 1 (+x).
        EXPECT_EQ(g.portals[0].owner, 0);
        EXPECT_EQ(g.portals[0].leaf, 1);
        EXPECT_NEAR(g.portals[0].plane.normal.x, 1.0f, 1e-6f);
        EXPECT_EQ(g.portals[1].owner, 1);
        EXPECT_EQ(g.portals[1].leaf, 0);
        EXPECT_NEAR(g.portals[1].plane.normal.x, -1.0f, 1e-6f);
        EXPECT_EQ(g.portals[1].winding.points[0], g.portals[0].winding.points[3]);  // reversed
        // The file's hint flag reaches only the forward portal; the reverse one follows -hint.
        EXPECT_TRUE(g.portals[0].hint);
        EXPECT_EQ(g.portals[1].hint, hintSwitch);
        EXPECT_EQ(g.leafs[0].portals, std::vector<int>{0});
        EXPECT_EQ(g.leafs[1].portals, std::vector<int>{1});
    }
}

TEST(PortalFile, EmptyPortalListIsValid) {
    const PortalFile f = parsePortalFile("PRT1\n1\n0\n0\n", "x.prt");
    EXPECT_EQ(f.clusterCount, 1);
    EXPECT_TRUE(f.portals.empty());
}

struct BadInput {
    const char* name;
    std::string text;
    std::string expected;  // part of the message
};

class PortalFileBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(PortalFileBadInput, FailsWithOneLineNamingFileAndProblem) {
    const std::string message = errorOf(GetParam().text);
    ASSERT_FALSE(message.empty()) << "accepted";
    EXPECT_EQ(message.rfind("maps/x.prt: line ", 0), 0u) << message;
    EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    All, PortalFileBadInput,
    ::testing::Values(
        BadInput{"Empty", "", "empty file"},
        BadInput{"WrongMagic", "PRT2\n2\n1\n0\n", "not a portal file"},
        BadInput{"MissingCounts", "PRT1\n2\n", "header: missing portals"},
        BadInput{"NoFaceCount", "PRT1\n2\n1\n", "header: missing solid faces"},
        BadInput{"NegativeCount", "PRT1\n2\n-1\n0\n", "negative portals"},
        BadInput{"TooManyPortals", "PRT1\n2\n200000\n0\n", "at most 131072"},
        BadInput{"TruncatedPortals", "PRT1\n2\n2\n0\n3 0 1 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n",
                 "file ends before portal 1"},
        BadInput{"TruncatedPoints", "PRT1\n2\n1\n0\n4 0 1 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n",
                 "portal 0: file ends after 3 of its points"},
        BadInput{"TruncatedFaces", "PRT1\n2\n0\n1\n", "file ends before solid face 0"},
        BadInput{"ExtraText", std::string(kTwoClusters) + "3 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n",
                 "text after the 1 portals and 1 solid faces"},
        BadInput{"TwoPoints", "PRT1\n2\n1\n0\n2 0 1 0 (0 0 0 ) (1 0 0 )\n", "2 points (a winding needs at least 3)"},
        BadInput{"TooManyPoints", "PRT1\n2\n1\n0\n65 0 1 0\n", "65 points (at most 64)"},
        BadInput{"ClusterAboveCount", "PRT1\n2\n1\n0\n3 0 3 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n",
                 "cluster 3 out of range (the header says 2 clusters)"},
        BadInput{"ClusterEqualsCount", "PRT1\n2\n1\n0\n3 2 0 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n", "cluster 2 out of range"},
        BadInput{"NegativeCluster", "PRT1\n2\n1\n0\n3 -1 0 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n", "cluster -1 out of range"},
        BadInput{"FaceClusterOutOfRange", "PRT1\n2\n0\n1\n3 5 (0 0 0 ) (1 0 0 ) (1 1 0 )\n", "solid face 0: cluster 5"},
        BadInput{"MissingFlags", "PRT1\n2\n1\n0\n3 0 1 (0 0 0 ) (1 0 0 ) (1 1 0 )\n", "flags expected"},
        BadInput{"BadPoint", "PRT1\n2\n1\n0\n3 0 1 0 (0 0 0 ) (1 x 0 ) (1 1 0 )\n", "point 1 is not"},
        BadInput{"UnclosedPoint", "PRT1\n2\n1\n0\n3 0 1 0 (0 0 0 (1 0 0 ) (1 1 0 )\n", "point 0 lacks its closing"},
        BadInput{"InfiniteCoordinate", "PRT1\n2\n1\n0\n3 0 1 0 (0 0 0 ) (inf 0 0 ) (1 1 0 )\n", "not a finite coordinate"},
        BadInput{"HugeNumber", "PRT1\n99999999999999999999\n0\n0\n", "out of range"}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return std::string(info.param.name); });

TEST(PortalFile, ErrorLineNumberPointsAtTheBadLine) {
    const std::string message = errorOf("PRT1\n2\n2\n0\n3 0 1 0 (0 0 0 ) (1 0 0 ) (1 1 0 )\n3 0 9 0 (0 0 0 )\n");
    EXPECT_NE(message.find("line 6: portal 1: cluster 9"), std::string::npos) << message;
}

}  // namespace
}  // namespace q3::vis
