#include "synthetic_bsp.h"

#include "sh_grid_lump.h"

#include <cstring>
#include <stdexcept>

namespace q3::bsp::test {

namespace {

Shader makeShader(const char* name, int32_t surfaceFlags, int32_t contentFlags) {
    Shader s{};
    std::strncpy(s.name, name, sizeof s.name - 1);
    s.surfaceFlags = surfaceFlags;
    s.contentFlags = contentFlags;
    return s;
}

DrawVert makeVert(float x, float y, float z, float s, float t) {
    DrawVert v{};
    v.xyz[0] = x;
    v.xyz[1] = y;
    v.xyz[2] = z;
    v.st[0] = s;
    v.st[1] = t;
    v.lightmap[0] = s * 0.5f;
    v.lightmap[1] = t * 0.5f;
    v.normal[2] = 1.0f;
    v.color[0] = v.color[1] = v.color[2] = v.color[3] = 255;
    return v;
}

}  // namespace

Bsp makeSyntheticBsp() {
    Bsp bsp;
    bsp.entities =
        "{\n\"classname\" \"worldspawn\"\n\"message\" \"synthetic\"\n}\n"
        "{\n\"classname\" \"light\"\n\"origin\" \"0 0 64\"\n\"light\" \"300\"\n}\n";
    bsp.entities += '\0';

    bsp.shaders = {makeShader("textures/base/wall", 0, 1), makeShader("textures/fog/thick", 0, 0x40)};
    // Axis planes in pairs: +X, -X, +Y, -Y, +Z, -Z, each 128 units from the origin.
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            Plane p{};
            p.normal[axis] = sign;
            p.dist = 128.0f;
            bsp.planes.push_back(p);
        }
    }
    Node node{};
    node.planeNum = 4;
    node.children[0] = -1;  // leaf 0
    node.children[1] = -2;  // leaf 1
    for (int i = 0; i < 3; ++i) {
        node.mins[i] = -128;
        node.maxs[i] = 128;
    }
    bsp.nodes = {node};

    Leaf open{};
    open.cluster = 0;
    open.firstLeafSurface = 0;
    open.numLeafSurfaces = 2;
    open.firstLeafBrush = 0;
    open.numLeafBrushes = 1;
    Leaf solid{};
    solid.cluster = -1;
    solid.area = -1;
    solid.firstLeafSurface = 2;
    solid.firstLeafBrush = 1;
    bsp.leafs = {open, solid};
    bsp.leafSurfaces = {0, 1};
    bsp.leafBrushes = {0};

    Model world{};
    for (int i = 0; i < 3; ++i) {
        world.mins[i] = -128.0f;
        world.maxs[i] = 128.0f;
    }
    world.numSurfaces = 2;
    world.numBrushes = 1;
    bsp.models = {world};

    bsp.brushes = {Brush{0, 6, 0}};
    for (int32_t i = 0; i < 6; ++i) bsp.brushSides.push_back(BrushSide{i, i == 5 ? 1 : 0});
    Fog fog{};
    std::strncpy(fog.shader, "textures/fog/thick", sizeof fog.shader - 1);
    fog.brushNum = 0;
    fog.visibleSide = 5;
    bsp.fogs = {fog};

    // Surface 0: a planar quad (verts 0-3, two triangles). Surface 1: a 3x3 patch (verts 4-12).
    bsp.drawVerts = {makeVert(-64, -64, 0, 0, 0), makeVert(64, -64, 0, 1, 0), makeVert(64, 64, 0, 1, 1),
                     makeVert(-64, 64, 0, 0, 1)};
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x)
            bsp.drawVerts.push_back(makeVert(-32.0f + 32 * x, -32.0f + 32 * y, 64.0f + (x == 1 && y == 1 ? 16 : 0),
                                             0.5f * x, 0.5f * y));
    bsp.drawIndexes = {0, 1, 2, 0, 2, 3};

    Surface quad{};
    quad.shaderNum = 0;
    quad.fogNum = -1;
    quad.surfaceType = MST_PLANAR;
    quad.firstVert = 0;
    quad.numVerts = 4;
    quad.firstIndex = 0;
    quad.numIndexes = 6;
    quad.lightmapNum = 0;
    quad.lightmapWidth = quad.lightmapHeight = 8;
    quad.lightmapVecs[2][2] = 1.0f;
    Surface patch{};
    patch.shaderNum = 0;
    patch.fogNum = 0;
    patch.surfaceType = MST_PATCH;
    patch.firstVert = 4;
    patch.numVerts = 9;
    patch.firstIndex = 6;
    patch.lightmapNum = kLightmapByVertex;
    patch.patchWidth = 3;
    patch.patchHeight = 3;
    bsp.surfaces = {quad, patch};

    bsp.lightmaps.resize(kLightmapPageBytes);
    for (size_t i = 0; i < bsp.lightmaps.size(); ++i) bsp.lightmaps[i] = static_cast<uint8_t>(i * 7 + 3);
    for (int i = 0; i < 8; ++i) {
        GridPoint g{};
        g.ambient[0] = static_cast<uint8_t>(10 + i);
        g.directed[1] = static_cast<uint8_t>(100 + i);
        g.latLong[0] = static_cast<uint8_t>(i * 16);
        bsp.lightGrid.push_back(g);
    }
    bsp.visibility = {1, 0, 0, 0, 1, 0, 0, 0, 0x01};
    return bsp;
}

std::vector<uint8_t> makeShGridLump(int bx, int by, int bz) {
    sh::GridSH grid;
    for (int axis = 0; axis < 3; ++axis) {
        grid.mins[axis] = -128.0f + axis;
        grid.size[axis] = 32.0f;
    }
    grid.bounds[0] = bx;
    grid.bounds[1] = by;
    grid.bounds[2] = bz;
    grid.points.resize(static_cast<size_t>(bx) * by * bz);
    float value = 0.25f;
    for (sh::GridPointSH& p : grid.points)
        for (auto& coeff : p.coeffs)
            for (float& c : coeff) c = (value += 0.125f);
    return sh::encodeGridLump(grid);
}

std::vector<RawEntry> rawEntries(std::span<const uint8_t> file, int count) {
    if (file.size() < 8 + 8 * static_cast<size_t>(count)) throw std::runtime_error("file shorter than its header");
    std::vector<RawEntry> out(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        std::memcpy(&out[static_cast<size_t>(i)].offset, file.data() + 8 + 8 * i, 4);
        std::memcpy(&out[static_cast<size_t>(i)].length, file.data() + 12 + 8 * i, 4);
    }
    return out;
}

std::vector<uint8_t> rawLump(std::span<const uint8_t> file, const RawEntry& entry) {
    if (entry.length == 0) return {};
    if (entry.offset < 0 || entry.length < 0 || static_cast<size_t>(entry.offset) + entry.length > file.size())
        throw std::runtime_error("raw entry outside the file");
    return std::vector<uint8_t>(file.begin() + entry.offset, file.begin() + entry.offset + entry.length);
}

void storeI32(std::vector<uint8_t>& file, size_t at, int32_t value) { std::memcpy(file.data() + at, &value, 4); }
void storeU32(std::vector<uint8_t>& file, size_t at, uint32_t value) { std::memcpy(file.data() + at, &value, 4); }

void setRawEntry(std::vector<uint8_t>& file, int lump, int32_t offset, int32_t length) {
    storeI32(file, 8 + 8 * static_cast<size_t>(lump), offset);
    storeI32(file, 12 + 8 * static_cast<size_t>(lump), length);
}

std::vector<uint8_t> buildRawImage(int32_t version, int entries, const std::vector<std::vector<uint8_t>>& lumps,
                                   const std::string& gap, const std::vector<int>& order, int32_t emptyOffset) {
    std::vector<uint8_t> file(8 + 8 * static_cast<size_t>(entries), 0);
    std::memcpy(file.data(), "IBSP", 4);
    storeI32(file, 4, version);
    file.insert(file.end(), gap.begin(), gap.end());
    file.resize((file.size() + 3) & ~size_t(3), 0);
    for (int lump : order) {
        const std::vector<uint8_t>& data = lumps.at(static_cast<size_t>(lump));
        const int32_t offset = static_cast<int32_t>(file.size());
        setRawEntry(file, lump, data.empty() ? (emptyOffset < 0 ? offset : emptyOffset) : offset,
                    static_cast<int32_t>(data.size()));
        file.insert(file.end(), data.begin(), data.end());
        file.resize((file.size() + 3) & ~size_t(3), 0);
    }
    return file;
}

}  // namespace q3::bsp::test
