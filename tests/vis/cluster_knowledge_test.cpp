// What finished portals tell about pairs of clusters: seen both ways, hidden once a cluster is done.
#include "cluster_knowledge.h"
#include "portal_file.h"
#include "vis_graph.h"

#include <gtest/gtest.h>

namespace q3::vis {
namespace {

// Three rooms in a row, 0 | 1 | 2: portal 0 (in room 0, into 1), 1 (in 1, into 0), 2 (in 1,
// into 2), 3 (in 2, into 1).
VisGraph threeRooms() {
    return buildVisGraph(parsePortalFile("PRT1\n3\n2\n0\n4 0 1 0 (0 0 0 ) (0 10 0 ) (0 10 10 ) (0 0 10 )\n"
                                         "4 1 2 0 (10 0 0 ) (10 10 0 ) (10 10 10 ) (10 0 10 )\n",
                                         "rooms.prt"),
                         false);
}

// The finished rows the knowledge reads: one row of cluster bits per portal.
struct Results {
    BitMatrix rows{4, 3};
    void set(int portal, std::initializer_list<int> clusters) {
        for (int c : clusters) setBit(rows.row(static_cast<size_t>(portal)), static_cast<size_t>(c));
    }
};

TEST(ClusterKnowledge, ASeenClusterIsKnownFromBothEnds) {
    const VisGraph graph = threeRooms();
    Results results;
    ClusterKnowledge known(graph, results.rows);
    EXPECT_EQ(known.home(0), 0);
    EXPECT_EQ(known.home(2), 1);
    EXPECT_EQ(known.home(3), 2);
    EXPECT_FALSE(testBit(known.seen(2), 0));
    results.set(0, {1, 2});  // room 0 sees rooms 1 and 2 through portal 0
    known.learn(0);
    EXPECT_TRUE(testBit(known.seen(0), 2));
    EXPECT_TRUE(testBit(known.seen(2), 0));  // so room 2 sees room 0
    EXPECT_TRUE(testBit(known.seen(1), 0));
    EXPECT_FALSE(testBit(known.seen(2), 1));  // nothing said about 2 and 1 yet
}

TEST(ClusterKnowledge, ADoneClusterHidesWhatItsRowMisses) {
    const VisGraph graph = threeRooms();
    Results results;
    ClusterKnowledge known(graph, results.rows);
    // Room 2 has one portal: once it is done seeing room 1 only, room 0 cannot see room 2.
    EXPECT_TRUE(testBit(known.possible(0), 2));
    results.set(3, {1});
    known.learn(3);
    EXPECT_FALSE(testBit(known.possible(0), 2));
    EXPECT_TRUE(testBit(known.possible(1), 2));
    EXPECT_TRUE(testBit(known.possible(2), 2));
    // Room 1 is not done until both its portals are; then its row is both portals' rows.
    results.set(1, {0});
    known.learn(1);
    EXPECT_TRUE(testBit(known.possible(2), 1));
    results.set(2, {2});
    known.learn(2);
    EXPECT_TRUE(testBit(known.possible(0), 1));
    EXPECT_TRUE(testBit(known.possible(2), 1));
}

}  // namespace
}  // namespace q3::vis
