#include "light_cache_test_bsp.h"

#include <algorithm>
#include <cstring>

#include "sh_test_support.h"

namespace q3::sh::test {
namespace {

constexpr float kWorldExtent = 8192;

void appendI32(std::vector<uint8_t>& bytes, int32_t value) {
    bytes.resize(bytes.size() + 4);
    putU32(bytes, bytes.size() - 4, uint32_t(value));
}

void appendPlane(std::vector<uint8_t>& planes, float nx, float ny, float nz, float dist) {
    for (float v : {nx, ny, nz, dist}) appendF32(planes, v);
}

std::vector<uint8_t> shaderLump() {
    struct Shader {
        const char* name;
        int32_t surfaceFlags, contents;
    };
    const Shader shaders[kShaderCount] = {{"textures/test/solid", 0, 1},
                                          {"textures/test/sky", 0x4, 1},
                                          {"textures/test/water", 0, 0x20},
                                          {"textures/test/glass", 0, 1 | 0x20000000}};
    std::vector<uint8_t> lump;
    for (const Shader& s : shaders) {
        const size_t at = lump.size();
        lump.resize(at + 64, 0);
        std::memcpy(lump.data() + at, s.name, std::strlen(s.name));
        appendI32(lump, s.surfaceFlags);
        appendI32(lump, s.contents);
    }
    return lump;
}

bool touches(const TestBox& box, const float mins[3], const float maxs[3]) {
    for (int axis = 0; axis < 3; ++axis)
        if (box.mins[axis] > maxs[axis] || box.maxs[axis] < mins[axis]) return false;
    return true;
}

struct TreeWriter {
    TreeWriter(const TestMap& m, int32_t firstPlane) : map(m), firstSplitPlane(firstPlane) {}
    const TestMap& map;
    int32_t firstSplitPlane;
    std::vector<uint8_t> nodes, leafs, leafBrushes;
    int32_t nodeCount = 0, leafCount = 0, leafBrushCount = 0;

    // Returns the child reference of the subtree for `depth` over the region.
    int32_t write(size_t depth, const float mins[3], const float maxs[3]) {
        if (depth == map.splits.size()) return -1 - writeLeaf(mins, maxs);
        const int32_t index = nodeCount++;
        const size_t at = nodes.size();
        nodes.resize(at + 36, 0);
        const TestSplit split = map.splits[depth];
        float frontMins[3], backMaxs[3];
        std::copy(mins, mins + 3, frontMins);
        std::copy(maxs, maxs + 3, backMaxs);
        frontMins[split.axis] = std::max(mins[split.axis], split.dist);
        backMaxs[split.axis] = std::min(maxs[split.axis], split.dist);
        const int32_t front = write(depth + 1, frontMins, maxs);
        const int32_t back = write(depth + 1, mins, backMaxs);
        putU32(nodes, at, uint32_t(firstSplitPlane + int32_t(depth)));
        putU32(nodes, at + 4, uint32_t(front));
        putU32(nodes, at + 8, uint32_t(back));
        for (int axis = 0; axis < 3; ++axis) {
            putU32(nodes, at + 12 + 4 * axis, uint32_t(int32_t(mins[axis])));
            putU32(nodes, at + 24 + 4 * axis, uint32_t(int32_t(maxs[axis])));
        }
        return index;
    }

    int32_t writeLeaf(const float mins[3], const float maxs[3]) {
        const int32_t first = leafBrushCount;
        for (size_t b = 0; b < map.boxes.size(); ++b)
            if (touches(map.boxes[b], mins, maxs)) {
                appendI32(leafBrushes, int32_t(b));
                ++leafBrushCount;
            }
        appendI32(leafs, map.cluster ? map.cluster(mins, maxs) : 0);
        appendI32(leafs, 0);  // area
        for (int axis = 0; axis < 3; ++axis) appendI32(leafs, int32_t(mins[axis]));
        for (int axis = 0; axis < 3; ++axis) appendI32(leafs, int32_t(maxs[axis]));
        appendI32(leafs, 0);  // leaf surfaces
        appendI32(leafs, 0);
        appendI32(leafs, first);
        appendI32(leafs, leafBrushCount - first);
        return leafCount++;
    }
};

}  // namespace

WorldLight testPointLight(float x, float y, float z, float intensity) {
    WorldLight l;
    l.origin = {x, y, z};
    l.intensity = {intensity, intensity, intensity};
    l.falloffConstants = {16, 0, 0, 0};
    l.cluster = 0;
    return l;
}

TestLumps testLumps(const TestMap& map) {
    TestLumps out;
    out.lumps.assign(map.grid ? 19 : 17, {});
    out.lumps[1] = shaderLump();
    std::vector<uint8_t>& planes = out.lumps[2];
    std::vector<uint8_t>& brushes = out.lumps[8];
    std::vector<uint8_t>& sides = out.lumps[9];
    int32_t sideCount = 0;
    for (const TestBox& box : map.boxes) {
        appendI32(brushes, sideCount);
        appendI32(brushes, 6);
        appendI32(brushes, box.shader);
        for (int axis = 0; axis < 3; ++axis)
            for (int sign : {1, -1}) {
                float n[3] = {0, 0, 0};
                n[axis] = float(sign);
                appendPlane(planes, n[0], n[1], n[2], sign > 0 ? box.maxs[axis] : -box.mins[axis]);
                appendI32(sides, int32_t(planes.size() / 16 - 1));
                appendI32(sides, box.shader);
                ++sideCount;
            }
    }
    TreeWriter tree(map, int32_t(planes.size() / 16));
    for (const TestSplit& split : map.splits) {
        float n[3] = {0, 0, 0};
        n[split.axis] = 1;
        appendPlane(planes, n[0], n[1], n[2], split.dist);
    }
    const float mins[3] = {-kWorldExtent, -kWorldExtent, -kWorldExtent};
    const float maxs[3] = {kWorldExtent, kWorldExtent, kWorldExtent};
    tree.write(0, mins, maxs);
    out.lumps[3] = tree.nodes;
    out.lumps[4] = tree.leafs;
    out.lumps[6] = tree.leafBrushes;

    float worldMins[3] = {0, 0, 0}, worldMaxs[3] = {0, 0, 0};
    for (const TestBox& box : map.boxes)
        for (int axis = 0; axis < 3; ++axis) {
            worldMins[axis] = std::min(worldMins[axis], box.mins[axis]);
            worldMaxs[axis] = std::max(worldMaxs[axis], box.maxs[axis]);
        }
    out.lumps[7] = worldModelLump(worldMins, worldMaxs);

    if (map.visible) {
        const int32_t rowBytes = (map.numClusters + 7) / 8;
        std::vector<uint8_t>& vis = out.lumps[16];
        appendI32(vis, map.numClusters);
        appendI32(vis, rowBytes);
        for (int32_t from = 0; from < map.numClusters; ++from) {
            std::vector<uint8_t> row(size_t(rowBytes), 0);
            for (int32_t to = 0; to < map.numClusters; ++to)
                if (map.visible(from, to)) row[size_t(to >> 3)] |= uint8_t(1u << (to & 7));
            vis.insert(vis.end(), row.begin(), row.end());
        }
    }
    if (map.grid) out.lumps[18] = encodeGridLump(*map.grid);
    if (!map.lights.empty()) out.worldLights = encodeWorldLights(map.lights);
    return out;
}

std::vector<uint8_t> assembleTestBsp(const TestLumps& lumps) {
    std::vector<BspxEntry> bspx;
    if (!lumps.worldLights.empty()) bspx.push_back({kWorldLightsLumpName, lumps.worldLights});
    return buildBsp(lumps.lumps.size() == 19 ? 47 : 46, int(lumps.lumps.size()), lumps.lumps, bspx);
}

std::vector<uint8_t> buildTestBsp(const TestMap& map) { return assembleTestBsp(testLumps(map)); }

TestMap roomWithPillar() {
    TestMap map;
    const float in = 256, wall = 16;
    map.boxes = {
        {{-in - wall, -in - wall, -wall}, {in + wall, in + wall, 0}},         // floor
        {{-in - wall, -in - wall, in}, {in + wall, in + wall, in + wall}},    // ceiling
        {{-in - wall, -in - wall, 0}, {-in, in + wall, in}},                  // -x wall
        {{in, -in - wall, 0}, {in + wall, in + wall, in}},                    // +x wall
        {{-in, -in - wall, 0}, {in, -in, in}},                                // -y wall
        {{-in, in, 0}, {in, in + wall, in}},                                  // +y wall
        {{-32, -32, 0}, {32, 32, in}},                                        // pillar
    };
    map.splits = {{0, 0}, {0, 32}, {0, -32}, {1, 32}, {1, -32}, {2, 128}};
    map.lights = {testPointLight(-200, 0, 128, 40000)};
    return map;
}

}  // namespace q3::sh::test
