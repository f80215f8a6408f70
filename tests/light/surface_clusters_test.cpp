// Clusters of a surface: the leafs listing it whose stored bounds touch its bounds.
#include <gtest/gtest.h>

#include <vector>

#include "surface_lighting.h"

namespace q3::light {
namespace {

// One wall face at y = -57.5 (x 0..64, z 0..64) listed by two leafs: leaf 0's integer box reaches
// y = -58, leaf 1's box stops at y = -57, half a unit short of the face.
bsp::Bsp wallListedByTwoLeafs() {
    bsp::Bsp b;
    for (float x : {0.0f, 64.0f})
        for (float z : {0.0f, 64.0f}) {
            bsp::DrawVert v{};
            v.xyz[0] = x;
            v.xyz[1] = -57.5f;
            v.xyz[2] = z;
            b.drawVerts.push_back(v);
        }
    bsp::Surface s{};
    s.surfaceType = bsp::MST_PLANAR;
    s.firstVert = 0;
    s.numVerts = 4;
    b.surfaces = {s};
    b.leafSurfaces = {0, 0};
    b.leafs = {{3, 0, {-8, -58, -8}, {72, -50, 72}, 0, 1, 0, 0}, {5, 0, {-8, -57, -8}, {72, 0, 72}, 1, 1, 0, 0}};
    return b;
}

TEST(SurfaceClusters, LeafWhoseBoundsMissTheSurfaceBringsNoCluster) {
    const bsp::Bsp b = wallListedByTwoLeafs();
    const std::vector<Vec3> offsets(1);
    EXPECT_EQ(surfaceClusterLists(b, offsets)[0], (std::vector<int>{3}));
}

TEST(SurfaceClusters, BoundsAreTakenWhereTheModelOriginPutsTheSurface) {
    const bsp::Bsp b = wallListedByTwoLeafs();
    const std::vector<Vec3> offsets{Vec3{0, 8, 0}};  // the face now lies at y = -49.5
    EXPECT_EQ(surfaceClusterLists(b, offsets)[0], (std::vector<int>{5}));
}

}  // namespace
}  // namespace q3::light
