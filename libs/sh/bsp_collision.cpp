// Loading of the BSP tree, brushes and visibility for light occlusion. Every count and index comes
// from the file, so each is checked against what it points into before anything is kept.
#include "bsp_collision.h"

#include <cmath>

#include "le_bytes.h"

namespace q3::sh {
namespace {

constexpr size_t kShaderBytes = 72;  // char name[64]; int surfaceFlags; int contentFlags
constexpr size_t kPlaneBytes = 16;
constexpr size_t kNodeBytes = 36;
constexpr size_t kLeafBytes = 48;
constexpr size_t kBrushBytes = 12;
constexpr size_t kSideBytes = 8;

std::string lumpError(const char* lump, const std::string& what) { return std::string("BSP ") + lump + " lump: " + what; }

// Records of a lump; a size that is not a whole number of records is an error.
bool recordCount(const ByteRange& lump, size_t recordBytes, const char* name, size_t& count, std::string& error) {
    if (lump.size % recordBytes != 0) {
        error = lumpError(name, std::to_string(lump.size) + " bytes is not a multiple of " + std::to_string(recordBytes));
        return false;
    }
    count = lump.size / recordBytes;
    if (count > size_t(INT32_MAX)) {
        error = lumpError(name, "more than 2^31 records");
        return false;
    }
    return true;
}

bool inRange(int64_t index, size_t count) { return index >= 0 && uint64_t(index) < count; }

// [first, first + count) inside [0, total), in 64-bit arithmetic.
bool spanInside(int32_t first, int32_t count, size_t total) {
    return first >= 0 && count >= 0 && uint64_t(first) + uint64_t(count) <= total;
}

std::string readShaderFlags(const ByteRange& lump, std::vector<int32_t>& surfaceFlags,
                            std::vector<int32_t>& contentFlags) {
    size_t count = 0;
    std::string error;
    if (!recordCount(lump, kShaderBytes, "shaders", count, error)) return error;
    surfaceFlags.resize(count);
    contentFlags.resize(count);
    for (size_t i = 0; i < count; ++i) {
        surfaceFlags[i] = le::readI32(lump.data + i * kShaderBytes + 64);
        contentFlags[i] = le::readI32(lump.data + i * kShaderBytes + 68);
    }
    return {};
}

std::string readPlanes(const ByteRange& lump, std::vector<CollisionPlane>& planes) {
    size_t count = 0;
    std::string error;
    if (!recordCount(lump, kPlaneBytes, "planes", count, error)) return error;
    planes.resize(count);
    for (size_t i = 0; i < count; ++i) {
        const uint8_t* p = lump.data + i * kPlaneBytes;
        CollisionPlane& plane = planes[i];
        for (int axis = 0; axis < 3; ++axis) plane.normal[axis] = le::readF32(p + 4 * axis);
        plane.dist = le::readF32(p + 12);
        for (float v : {plane.normal[0], plane.normal[1], plane.normal[2], plane.dist})
            if (!std::isfinite(v) || std::fabs(v) > 1e9f)
                return lumpError("planes", "plane " + std::to_string(i) + " is not finite");
    }
    return {};
}

// Each node and leaf is reached at most once, and a child node always has a larger index than its
// parent: the graph is a tree, so every walk ends and visits each node once at most.
std::string readNodes(const ByteRange& lump, size_t planeCount, size_t leafCount, std::vector<CollisionNode>& nodes) {
    size_t count = 0;
    std::string error;
    if (!recordCount(lump, kNodeBytes, "nodes", count, error)) return error;
    if (count == 0) return lumpError("nodes", "empty (the map has no BSP tree)");
    nodes.resize(count);
    std::vector<uint8_t> nodeReached(count, 0), leafReached(leafCount, 0);
    std::vector<uint16_t> depth(count, 1);
    for (size_t i = 0; i < count; ++i) {
        const uint8_t* p = lump.data + i * kNodeBytes;
        CollisionNode& node = nodes[i];
        node.plane = le::readI32(p);
        if (!inRange(node.plane, planeCount))
            return lumpError("nodes", "node " + std::to_string(i) + " plane " + std::to_string(node.plane) +
                                          " is not in 0.." + std::to_string(int64_t(planeCount) - 1));
        for (int side = 0; side < 2; ++side) {
            const int32_t child = le::readI32(p + 4 + 4 * side);
            node.children[side] = child;
            const std::string where = "node " + std::to_string(i) + " child " + std::to_string(child);
            if (child >= 0) {
                if (uint64_t(child) <= i || uint64_t(child) >= count)
                    return lumpError("nodes", where + " is not a later node (" + std::to_string(count) + " nodes)");
                if (nodeReached[child]++) return lumpError("nodes", where + " is reached twice");
                depth[child] = uint16_t(depth[i] + 1);
                if (depth[child] > kMaxTreeDepth)
                    return lumpError("nodes", "the tree is deeper than " + std::to_string(kMaxTreeDepth) + " levels");
            } else {
                const int64_t leaf = -1 - int64_t(child);
                if (!inRange(leaf, leafCount))
                    return lumpError("nodes", where + " names leaf " + std::to_string(leaf) + " of " +
                                                  std::to_string(leafCount));
                if (leafReached[leaf]++) return lumpError("nodes", where + " is reached twice");
            }
        }
    }
    return {};
}

std::string readVisibility(const ByteRange& lump, BspCollision& out) {
    out.numClusters = 0;
    out.clusterBytes = 0;
    out.visBits.clear();
    if (lump.empty()) return {};
    if (lump.size < 8) return lumpError("visibility", std::to_string(lump.size) + " bytes, shorter than its 8-byte header");
    const int32_t clusters = le::readI32(lump.data), bytes = le::readI32(lump.data + 4);
    if (clusters < 0 || bytes < 0)
        return lumpError("visibility", "negative cluster count " + std::to_string(clusters) + " or row size " +
                                           std::to_string(bytes));
    if (uint64_t(bytes) * 8 < uint64_t(clusters))
        return lumpError("visibility", "rows of " + std::to_string(bytes) + " bytes cannot hold " +
                                           std::to_string(clusters) + " clusters");
    const uint64_t need = 8 + uint64_t(clusters) * uint64_t(bytes);
    if (need > lump.size)
        return lumpError("visibility", std::to_string(clusters) + " clusters of " + std::to_string(bytes) +
                                           " bytes need " + std::to_string(need) + " bytes, the lump has " +
                                           std::to_string(lump.size));
    out.numClusters = clusters;
    out.clusterBytes = clusters > 0 ? bytes : 0;
    out.visBits.assign(lump.data + 8, lump.data + need);
    return {};
}

}  // namespace

bool brushBlocksLight(int32_t contentFlags) {
    return (contentFlags & kContentsSolid) != 0 && (contentFlags & kContentsTranslucent) == 0;
}

std::string loadBspCollision(const BspDirectory& dir, BspCollision& out) {
    out = BspCollision{};
    std::vector<int32_t> surfaceFlags, contentFlags;
    std::string error = readShaderFlags(dir.lumps[kLumpShaders], surfaceFlags, contentFlags);
    if (error.empty()) error = readPlanes(dir.lumps[kLumpPlanes], out.planes);
    if (error.empty()) error = readVisibility(dir.lumps[kLumpVisibility], out);
    if (!error.empty()) return error;

    size_t sideCount = 0, brushCount = 0, leafBrushCount = 0, leafCount = 0;
    if (!recordCount(dir.lumps[kLumpBrushSides], kSideBytes, "brushsides", sideCount, error) ||
        !recordCount(dir.lumps[kLumpBrushes], kBrushBytes, "brushes", brushCount, error) ||
        !recordCount(dir.lumps[kLumpLeafBrushes], 4, "leafbrushes", leafBrushCount, error) ||
        !recordCount(dir.lumps[kLumpLeafs], kLeafBytes, "leafs", leafCount, error))
        return error;

    out.sides.resize(sideCount);
    for (size_t i = 0; i < sideCount; ++i) {
        const uint8_t* p = dir.lumps[kLumpBrushSides].data + i * kSideBytes;
        const int32_t plane = le::readI32(p), shader = le::readI32(p + 4);
        if (!inRange(plane, out.planes.size()))
            return lumpError("brushsides", "side " + std::to_string(i) + " plane " + std::to_string(plane) +
                                               " is not in 0.." + std::to_string(int64_t(out.planes.size()) - 1));
        if (!inRange(shader, surfaceFlags.size()))
            return lumpError("brushsides", "side " + std::to_string(i) + " shader " + std::to_string(shader) +
                                               " is not in 0.." + std::to_string(int64_t(surfaceFlags.size()) - 1));
        out.sides[i] = {plane, (surfaceFlags[shader] & kSurfaceSky) != 0};
    }

    std::vector<uint8_t> opaque(brushCount, 0);
    out.brushes.resize(brushCount);
    for (size_t i = 0; i < brushCount; ++i) {
        const uint8_t* p = dir.lumps[kLumpBrushes].data + i * kBrushBytes;
        const int32_t first = le::readI32(p), count = le::readI32(p + 4), shader = le::readI32(p + 8);
        if (!spanInside(first, count, sideCount))
            return lumpError("brushes", "brush " + std::to_string(i) + " sides " + std::to_string(first) + " + " +
                                            std::to_string(count) + " run past the " + std::to_string(sideCount) +
                                            " brush sides");
        if (!inRange(shader, contentFlags.size()))
            return lumpError("brushes", "brush " + std::to_string(i) + " shader " + std::to_string(shader) +
                                            " is not in 0.." + std::to_string(int64_t(contentFlags.size()) - 1));
        out.brushes[i] = {uint32_t(first), uint32_t(count)};
        opaque[i] = brushBlocksLight(contentFlags[shader]);
    }

    std::vector<int32_t> leafBrushes(leafBrushCount);
    for (size_t i = 0; i < leafBrushCount; ++i) {
        leafBrushes[i] = le::readI32(dir.lumps[kLumpLeafBrushes].data + 4 * i);
        if (!inRange(leafBrushes[i], brushCount))
            return lumpError("leafbrushes", "entry " + std::to_string(i) + " brush " + std::to_string(leafBrushes[i]) +
                                                " is not in 0.." + std::to_string(int64_t(brushCount) - 1));
    }

    // Each leaf keeps only its opaque brushes, so traces never look at water, clips or glass.
    out.leafs.resize(leafCount);
    for (size_t i = 0; i < leafCount; ++i) {
        const uint8_t* p = dir.lumps[kLumpLeafs].data + i * kLeafBytes;
        const int32_t cluster = le::readI32(p), first = le::readI32(p + 40), count = le::readI32(p + 44);
        const std::string where = "leaf " + std::to_string(i);
        if (cluster < -1 || (out.hasVisibility() && cluster >= out.numClusters))
            return lumpError("leafs", where + " cluster " + std::to_string(cluster) + " is not in -1.." +
                                          std::to_string(out.numClusters - 1) + " (visibility data)");
        if (!spanInside(first, count, leafBrushCount))
            return lumpError("leafs", where + " brushes " + std::to_string(first) + " + " + std::to_string(count) +
                                          " run past the " + std::to_string(leafBrushCount) + " leaf brushes");
        CollisionLeaf& leaf = out.leafs[i];
        leaf.cluster = cluster;
        leaf.firstBrush = uint32_t(out.leafBrushes.size());
        for (int32_t k = 0; k < count; ++k)
            if (opaque[leafBrushes[first + k]]) out.leafBrushes.push_back(uint32_t(leafBrushes[first + k]));
        leaf.brushCount = uint32_t(out.leafBrushes.size()) - leaf.firstBrush;
    }
    if (leafCount == 0) return lumpError("leafs", "empty (the map has no leaves)");
    return readNodes(dir.lumps[kLumpNodes], out.planes.size(), leafCount, out.nodes);
}

int32_t pointLeaf(const BspCollision& world, const float point[3]) {
    if (world.nodes.empty()) return 0;
    int32_t index = 0;
    while (index >= 0) {
        const CollisionNode& node = world.nodes[index];
        const CollisionPlane& plane = world.planes[node.plane];
        const float d = plane.normal[0] * point[0] + plane.normal[1] * point[1] + plane.normal[2] * point[2] - plane.dist;
        index = node.children[d < 0 ? 1 : 0];
    }
    return -1 - index;
}

bool clusterVisible(const BspCollision& world, int32_t from, int32_t to) {
    if (from < 0 || to < 0 || !world.hasVisibility()) return true;
    if (from >= world.numClusters || to >= world.numClusters) return true;  // not reachable after loading
    return (world.visBits[size_t(from) * size_t(world.clusterBytes) + size_t(to >> 3)] >> (to & 7)) & 1;
}

}  // namespace q3::sh
