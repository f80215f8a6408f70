// The parts of a Quake 3 BSP that a runtime needs to test whether light reaches a point: the node
// tree down to the leaves (which leaf and cluster holds a point), the opaque brushes of each leaf
// (for rays, as Quake 3's collision code clips a zero-size box against brushes), and the
// visibility lump (which clusters can see each other). Loaded from a BSP image with every index,
// count and float checked; no dependencies, no exceptions besides std::bad_alloc.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sh_bsp_scan.h"

namespace q3::sh {

// Shader flags (Quake 3's surfaceflags.h values) that decide what blocks light.
constexpr int32_t kContentsSolid = 0x1;
constexpr int32_t kContentsTranslucent = 0x20000000;
constexpr int32_t kSurfaceSky = 0x4;

// Deeper trees are refused: real maps stay below ~100 levels, and the walks recurse per level.
constexpr int kMaxTreeDepth = 1024;

struct CollisionPlane {
    float normal[3];
    float dist;
};

struct CollisionNode {
    int32_t plane;
    int32_t children[2];  // >= 0: node index (always above the parent's); < 0: leaf -1 - child
};

struct CollisionLeaf {
    int32_t cluster;      // -1: outside the map or in solid
    uint32_t firstBrush;  // into BspCollision::leafBrushes (opaque brushes only)
    uint32_t brushCount;
};

struct CollisionBrush {
    uint32_t firstSide;
    uint32_t sideCount;
};

struct CollisionSide {
    int32_t plane;
    bool sky;  // the side's shader has SURF_SKY: a sun ray entering here leaves the world
};

struct BspCollision {
    std::vector<CollisionPlane> planes;
    std::vector<CollisionNode> nodes;
    std::vector<CollisionLeaf> leafs;
    std::vector<uint32_t> leafBrushes;  // brush indices, only brushes that block light
    std::vector<CollisionBrush> brushes;
    std::vector<CollisionSide> sides;
    int32_t numClusters = 0;  // 0 with clusterBytes 0: no visibility data (nothing is culled)
    int32_t clusterBytes = 0;
    std::vector<uint8_t> visBits;  // numClusters rows of clusterBytes

    bool hasVisibility() const { return clusterBytes > 0; }
};

// A brush blocks light when its shader's contents hold CONTENTS_SOLID and not
// CONTENTS_TRANSLUCENT (q3map2 casts no shadow from translucent surfaces).
bool brushBlocksLight(int32_t contentFlags);

// Reads lumps 1, 2, 3, 4, 6, 8, 9 and 16 of `dir`. Returns an empty string or one line naming the
// lump and the fault (bad size, index out of range, non-finite plane, a node reached twice, a tree
// deeper than kMaxTreeDepth, a leaf cluster outside the visibility data, a short vis lump).
std::string loadBspCollision(const BspDirectory& dir, BspCollision& out);

// The leaf holding `point` (front side on ties, as Quake 3's CM_PointLeafnum).
int32_t pointLeaf(const BspCollision& world, const float point[3]);
// Whether cluster `to` is in the potentially visible set of cluster `from`; true when either is
// -1 or there is no visibility data.
bool clusterVisible(const BspCollision& world, int32_t from, int32_t to);

struct RayHit {
    bool hit = false;
    float fraction = 1;  // along start -> end where the first opaque brush is entered
    bool sky = false;    // the side entered there has SURF_SKY
};

// The first opaque brush the segment enters (stopAtAny: any one, for a plain occlusion test).
// Brushes holding `start` are passed through: a point sunk into a floor still sees above it.
RayHit traceRay(const BspCollision& world, const float start[3], const float end[3], bool stopAtAny);

}  // namespace q3::sh
