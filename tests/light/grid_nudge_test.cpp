// q3map2's rand() sequence and the grid-point nudges that draw from it (placeGridPointAsTraceGrid).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "bsp_tree.h"
#include "c_library_random.h"
#include "grid_blocks.h"

namespace q3::light {
namespace {

TEST(CLibraryRandom, FollowsTheGnuRandSequence) {
    // The values glibc's rand() returns after srand(1) (and srand(0), which it takes as 1).
    for (uint32_t seed : {0u, 1u}) {
        CLibraryRandom random(seed);
        EXPECT_EQ(random.next(), 1804289383);
        EXPECT_EQ(random.next(), 846930886);
        EXPECT_EQ(random.next(), 1681692777);
        EXPECT_EQ(random.next(), 1714636915);
        EXPECT_EQ(random.next(), 1957747793);
        random.discard(994);
        EXPECT_EQ(random.next(), 1143565421);  // the 1000th
    }
    CLibraryRandom other(12345);
    EXPECT_EQ(other.next(), 383100999);
    EXPECT_EQ(other.next(), 858300821);
    // Skipping ahead (long runs jump by powers of the step) lands where stepping does.
    for (uint64_t count : {0ull, 5ull, 30ull, 31ull, 124ull, 125ull, 512ull, 597ull, 1043ull, 4096ull, 4097ull,
                           597ull * 1000 + 17}) {
        CLibraryRandom stepped(7), skipped(7);
        (void)stepped.next();
        (void)skipped.next();
        for (uint64_t i = 0; i < count; ++i) (void)stepped.next();
        skipped.discard(count);
        for (int i = 0; i < 40; ++i) ASSERT_EQ(skipped.next(), stepped.next()) << count;
    }
    // Random(): the value times the float 1 / RAND_MAX.
    CLibraryRandom unit;
    EXPECT_FLOAT_EQ(unit.unit(), float(1804289383) * (1.0f / 2147483648.0f));
}

// Everything at x > 0 is open (cluster 0); x < 0 lies outside the world (no cluster).
bsp::Bsp halfOpenWorld() {
    bsp::Bsp b;
    bsp::Shader solid{};
    std::strcpy(solid.name, "textures/test/solid");
    b.shaders = {solid};
    b.planes = {{{1, 0, 0}, 0}};
    b.nodes = {{0, {-1, -2}, {-1000, -1000, -1000}, {1000, 1000, 1000}}};
    b.leafs = {{0, 0, {0, -1000, -1000}, {1000, 1000, 1000}, 0, 0, 0, 0},
               {-1, 0, {-1000, -1000, -1000}, {0, 1000, 1000}, 0, 0, 0, 0}};
    b.models = {{{-1000, -1000, -1000}, {1000, 1000, 1000}, 0, 0, 0, 0}};
    return b;
}

// The first of q3map2's tries that reaches x > -0.1 (the open side, planes being thick 0.1),
// written out independently: its index (-1 for none) and position.
int firstOpenTry(Vec3 origin, Vec3 cell, CLibraryRandom random, Vec3& position) {
    double step = 0;
    for (int k = 0; k < 199; ++k) {
        step += 0.005;
        float p[3];
        for (int axis = 0; axis < 3; ++axis)
            p[axis] = float(double(origin[axis]) + (double(random.unit()) - 0.5) * step * double(cell[axis]));
        if (p[0] > -0.1f) {
            position = {p[0], p[1], p[2]};
            return k;
        }
    }
    return -1;
}

TEST(GridNudges, PointsInSolidTakeTheFirstOpenTryDrawingInIndexOrder) {
    const bsp::Bsp b = halfOpenWorld();
    const BspTree tree(b);
    // Two rows of three points at x = -70 (half a cell from the open side: no try can get out),
    // x = -6 (nudged) and x = 58 (open), 64 units apart along y.
    const GridLattice grid{{3, 2, 1}, {-70, 0, 0}, {64, 64, 128}};
    const CLibraryRandom start;
    for (int threads : {1, 2}) {
        const auto placed = placeGridAsTraceGrid(&tree, grid, start, threads);
        ASSERT_EQ(placed.size(), 6u);
        // q3map2's order: every try of a point that stays in solid draws 3 values, and a nudged
        // point draws 3 per try up to its first open one.
        CLibraryRandom expected = start;
        for (int row = 0; row < 2; ++row) {
            const Vec3 y{0, 64.0f * float(row), 0};
            EXPECT_FALSE(placed[size_t(3 * row)]) << "row " << row;
            expected.discard(3 * kGridNudgeTries);
            Vec3 position;
            const int k = firstOpenTry(Vec3{-6, 0, 0} + y, grid.size, expected, position);
            ASSERT_GE(k, 0);
            expected.discard(3 * uint64_t(k + 1));
            const auto& nudged = placed[size_t(3 * row + 1)];
            ASSERT_TRUE(nudged) << "row " << row;
            EXPECT_TRUE(nudged->nudged);
            EXPECT_EQ(nudged->origin, position);
            EXPECT_EQ(nudged->cluster, 0);
            const auto& open = placed[size_t(3 * row + 2)];
            ASSERT_TRUE(open);
            EXPECT_FALSE(open->nudged);
            EXPECT_EQ(open->origin, (Vec3{58, 0, 0} + y));
        }
    }
}

TEST(GridNudges, TriesThatCannotBeFreeAreDrawnButNotTested) {
    const bsp::Bsp b = halfOpenWorld();
    const BspTree tree(b);
    const Vec3 cell{64, 64, 128};
    for (float x : {-0.5f, -3.0f, -6.0f, -12.0f, -20.0f, -28.0f, -31.0f, -31.9f, -33.0f, -40.0f}) {
        // Try k reaches at most half of 0.005 (k + 1) cells: no earlier try can reach x > -0.1.
        const int first = firstGridNudgeThatMayLeaveSolid(tree, {x, 0, 0}, cell);
        const int bound = int(std::floor((-x - 0.1f) / (0.5f * 0.005f * cell.x))) - 1;
        EXPECT_GE(first, std::min(std::max(bound, 0), kGridNudgeTries)) << x;
        EXPECT_LE(first, kGridNudgeTries) << x;
        if (x < -32.1f) {
            EXPECT_EQ(first, kGridNudgeTries) << x;
        }
        // Whatever try it starts from, the point lands where q3map2's first open try puts it, and
        // the sequence moves on by exactly the values those tries drew.
        const CLibraryRandom start(1234);
        Vec3 expected;
        const int k = firstOpenTry({x, 0, 0}, cell, start, expected);
        for (int from : {0, first}) {
            CLibraryRandom random = start;
            const auto placed = nudgeGridPointAsTraceGrid(tree, {x, 0, 0}, cell, random, from);
            CLibraryRandom after = start;
            after.discard(3 * uint64_t(k >= 0 ? k + 1 : kGridNudgeTries));
            EXPECT_EQ(random.next(), after.next()) << x << " from " << from;
            ASSERT_EQ(placed.has_value(), k >= 0) << x << " from " << from;
            if (placed) {
                EXPECT_EQ(placed->origin, expected) << x << " from " << from;
            }
        }
    }
}

}  // namespace
}  // namespace q3::light
