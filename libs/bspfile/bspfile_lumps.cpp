// Lump names, record sizes and the raw byte view of each lump.
#include "bspfile_internal.h"

namespace q3::bsp {

namespace {

constexpr std::string_view kLumpNames[kMaxLumps] = {
    "entities",  "shaders",     "planes",   "nodes",      "leafs",     "leafsurfaces",   "leafbrushes",
    "models",    "brushes",     "brushsides", "drawverts", "drawindexes", "fogs",          "surfaces",
    "lightmaps", "lightgrid",   "visibility", "advertisements", "lightgrid_sh",
};

constexpr size_t kRecordSizes[kMaxLumps] = {
    0,  // entities: text
    sizeof(Shader), sizeof(Plane), sizeof(Node), sizeof(Leaf), sizeof(int32_t), sizeof(int32_t),
    sizeof(Model), sizeof(Brush), sizeof(BrushSide), sizeof(DrawVert), sizeof(int32_t), sizeof(Fog),
    sizeof(Surface),
    0,  // lightmaps: pages whose size depends on the game
    sizeof(GridPoint),
    0,  // visibility: header + bit rows
    0,  // lump 17: advertisements in Quake Live, unused elsewhere
    0,  // lump 18: SH grid, checked by its own codec
};

}  // namespace

std::string_view lumpName(int lump) {
    if (lump < 0 || lump >= kMaxLumps) return "lump?";
    return kLumpNames[lump];
}

size_t lumpRecordSize(int lump) {
    if (lump < 0 || lump >= kMaxLumps) return 0;
    return kRecordSizes[lump];
}

namespace detail {

void fail(const std::string& file, std::string_view where, const std::string& what) {
    throw BspError(file + ": " + std::string(where) + ": " + what);
}

void failLump(const std::string& file, int lump, const std::string& what) { fail(file, lumpName(lump), what); }

}  // namespace detail

std::vector<uint8_t> lumpBytes(const Bsp& bsp, int lump) {
    using detail::bytesOf;
    switch (lump) {
        case LUMP_ENTITIES: return std::vector<uint8_t>(bsp.entities.begin(), bsp.entities.end());
        case LUMP_SHADERS: return bytesOf(bsp.shaders);
        case LUMP_PLANES: return bytesOf(bsp.planes);
        case LUMP_NODES: return bytesOf(bsp.nodes);
        case LUMP_LEAFS: return bytesOf(bsp.leafs);
        case LUMP_LEAFSURFACES: return bytesOf(bsp.leafSurfaces);
        case LUMP_LEAFBRUSHES: return bytesOf(bsp.leafBrushes);
        case LUMP_MODELS: return bytesOf(bsp.models);
        case LUMP_BRUSHES: return bytesOf(bsp.brushes);
        case LUMP_BRUSHSIDES: return bytesOf(bsp.brushSides);
        case LUMP_DRAWVERTS: return bytesOf(bsp.drawVerts);
        case LUMP_DRAWINDEXES: return bytesOf(bsp.drawIndexes);
        case LUMP_FOGS: return bytesOf(bsp.fogs);
        case LUMP_SURFACES: return bytesOf(bsp.surfaces);
        case LUMP_LIGHTMAPS: return bsp.lightmaps;
        case LUMP_LIGHTGRID: return bytesOf(bsp.lightGrid);
        case LUMP_VISIBILITY: return bsp.visibility;
        case LUMP_ADVERTISEMENTS: return bsp.lump17;
        case LUMP_LIGHTGRID_SH: return bsp.shGrid;
        default: break;
    }
    throw BspError("bsp: lump " + std::to_string(lump) + ": no such lump (valid: 0 to " +
                   std::to_string(kMaxLumps - 1) + ")");
}

void attachShGrid(Bsp& bsp, std::vector<uint8_t> lumpImage) {
    bsp.shGrid = std::move(lumpImage);
    bsp.version = kVersionQL;
    bsp.headerLumps = kMaxLumps;
}

void detachShGrid(Bsp& bsp) {
    bsp.shGrid.clear();
    bsp.version = kVersionQ3;
    bsp.headerLumps = bsp.lump17.empty() ? 17 : 18;
}

}  // namespace q3::bsp
