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

std::span<const uint8_t> lumpView(const Bsp& bsp, int lump) {
    using detail::bytesView;
    switch (lump) {
        case LUMP_ENTITIES: return {reinterpret_cast<const uint8_t*>(bsp.entities.data()), bsp.entities.size()};
        case LUMP_SHADERS: return bytesView(bsp.shaders);
        case LUMP_PLANES: return bytesView(bsp.planes);
        case LUMP_NODES: return bytesView(bsp.nodes);
        case LUMP_LEAFS: return bytesView(bsp.leafs);
        case LUMP_LEAFSURFACES: return bytesView(bsp.leafSurfaces);
        case LUMP_LEAFBRUSHES: return bytesView(bsp.leafBrushes);
        case LUMP_MODELS: return bytesView(bsp.models);
        case LUMP_BRUSHES: return bytesView(bsp.brushes);
        case LUMP_BRUSHSIDES: return bytesView(bsp.brushSides);
        case LUMP_DRAWVERTS: return bytesView(bsp.drawVerts);
        case LUMP_DRAWINDEXES: return bytesView(bsp.drawIndexes);
        case LUMP_FOGS: return bytesView(bsp.fogs);
        case LUMP_SURFACES: return bytesView(bsp.surfaces);
        case LUMP_LIGHTMAPS: return bsp.lightmaps;
        case LUMP_LIGHTGRID: return bytesView(bsp.lightGrid);
        case LUMP_VISIBILITY: return bsp.visibility;
        case LUMP_ADVERTISEMENTS: return bsp.lump17;
        case LUMP_LIGHTGRID_SH: return bsp.shGrid;
        default: break;
    }
    throw BspError("bsp: lump " + std::to_string(lump) + ": no such lump (valid: 0 to " +
                   std::to_string(kMaxLumps - 1) + ")");
}

std::vector<uint8_t> lumpBytes(const Bsp& bsp, int lump) {
    const std::span<const uint8_t> view = lumpView(bsp, lump);
    return std::vector<uint8_t>(view.begin(), view.end());
}

void attachShGrid(Bsp& bsp, std::vector<uint8_t> lumpImage) {
    bsp.shGrid = std::move(lumpImage);
    bsp.version = kVersionQL;
    bsp.headerLumps = kMaxLumps;
}

void detachShGrid(Bsp& bsp) {
    std::vector<uint8_t>().swap(bsp.shGrid);  // its memory too: clear() would keep up to 1 GiB reserved
    bsp.version = kVersionQ3;
    bsp.headerLumps = bsp.lump17.empty() ? 17 : 18;
}

}  // namespace q3::bsp
