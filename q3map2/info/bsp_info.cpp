// The -info report, laid out like q3map2's PrintBSPFileSizes: "%9d <name padded> %9d" per lump,
// count then bytes, with '*' after the lumps whose in-memory form differs from the file's.
#include "grid_stats.h"
#include "info_stage.h"
#include "world_lights.h"

#include <cinttypes>
#include <cstdio>
#include <string>

namespace q3::info {

namespace {

std::string printf9(const char* format, auto... values) {
    char buffer[256];
    std::snprintf(buffer, sizeof(buffer), format, values...);
    return buffer;
}

std::string lumpLine(const char* name, size_t count, size_t bytes, bool approximate = false) {
    return printf9("%9zu %-13s %9zu%s\n", count, name, bytes, approximate ? " *" : "");
}

template <class T>
std::string recordLine(const char* name, const std::vector<T>& records, bool approximate = false) {
    return lumpLine(name, records.size(), records.size() * sizeof(T), approximate);
}

std::string shGridSection(const std::vector<uint8_t>& lump, const std::string& where, const std::string& name) {
    sh::GridSH grid;
    std::string error;
    if (!sh::decodeGridLump(lump.data(), lump.size(), grid, error))
        throw bsp::BspError(name + ": " + where + ": " + error);
    ShGridStats stats = shGridStats(grid);
    std::string out = "SH grid (" + where + "):\n";
    out += printf9("  bounds       %d x %d x %d\n", grid.bounds[0], grid.bounds[1], grid.bounds[2]);
    out += printf9("  cell size    %g %g %g\n", grid.size[0], grid.size[1], grid.size[2]);
    out += printf9("  mins         %g %g %g\n", grid.mins[0], grid.mins[1], grid.mins[2]);
    out += printf9("  points       %" PRId64 "\n", stats.points);
    out += printf9("  bytes        %zu\n", lump.size());
    out += printf9("  coefficient 0 min %g max %g mean %g\n", stats.coeff0Min, stats.coeff0Max, stats.coeff0Mean);
    out += printf9("  all-zero points %" PRId64 "\n", stats.allZeroPoints);
    return out;
}

// Size and light count of a WORLDLIGHTS lump (a malformed one fails like a malformed SH grid).
std::string worldLightsSection(const std::vector<uint8_t>& lump, const std::string& name) {
    std::vector<sh::WorldLight> lights;
    std::string error;
    if (!sh::decodeWorldLights(lump.data(), lump.size(), lights, error)) throw bsp::BspError(name + ": BSPX " + error);
    size_t counts[3] = {0, 0, 0}, inGrid = 0;
    for (const sh::WorldLight& l : lights) {
        ++counts[uint32_t(l.type)];
        inGrid += (l.flags & sh::kWorldLightInShGrid) != 0;
    }
    std::string out = printf9("World lights (BSPX %s): %zu lights, %zu bytes\n", sh::kWorldLightsLumpName,
                              lights.size(), lump.size());
    out += printf9("  %zu point, %zu spot, %zu sun; %zu with their direct light in the SH grid\n", counts[0], counts[1],
                   counts[2], inGrid);
    return out;
}

std::string legacyGridSection(const bsp::Bsp& bsp, const std::vector<bsp::Entity>& entities) {
    if (bsp.models.empty()) return printf9("Legacy grid: %zu points stored, no model 0 to derive the engine's grid\n",
                                           bsp.lightGrid.size());
    float cellSize[3] = {64, 64, 128};
    if (!entities.empty())
        if (const std::string* value = entities.front().find("gridsize")) parseGridSize(*value, cellSize);
    LegacyGridLayout layout = legacyGridLayout(bsp.models[0].mins, bsp.models[0].maxs, cellSize);
    std::string out = printf9("Legacy grid: %zu points stored, engine expects %" PRId64
                              " (gridsize %g %g %g, bounds %d x %d x %d)\n",
                              bsp.lightGrid.size(), layout.points, cellSize[0], cellSize[1], cellSize[2],
                              layout.bounds[0], layout.bounds[1], layout.bounds[2]);
    if (!bsp.lightGrid.empty() && static_cast<int64_t>(bsp.lightGrid.size()) != layout.points)
        out += "  count mismatch: engines discard this light grid\n";
    return out;
}

}  // namespace

std::string formatBspInfo(const bsp::Bsp& bsp, const std::string& name, uintmax_t fileSize) {
    std::vector<bsp::Entity> entities = bsp::parseEntities(bsp.entities, name);
    size_t patches = 0, planar = 0, trisoup = 0, flares = 0, foliage = 0;
    for (const bsp::Surface& s : bsp.surfaces) {
        patches += s.surfaceType == bsp::MST_PATCH;
        planar += s.surfaceType == bsp::MST_PLANAR;
        trisoup += s.surfaceType == bsp::MST_TRIANGLE_SOUP;
        flares += s.surfaceType == bsp::MST_FLARE;
        foliage += s.surfaceType == bsp::MST_FOLIAGE;
    }

    std::string out = "---------------------------------\n" + name + "\n";
    out += printf9("File size: %ju bytes (%.2f MB)\n", fileSize, static_cast<double>(fileSize) / (1024.0 * 1024.0));
    out += printf9("Header: IBSP version %d, %d lump entries\n\n", bsp.version, bsp.headerLumps);

    out += "Abstracted BSP file components (*actual sizes may differ)\n";
    out += recordLine("models", bsp.models);
    out += recordLine("shaders", bsp.shaders);
    out += recordLine("brushes", bsp.brushes);
    out += recordLine("brushsides", bsp.brushSides, true);
    out += recordLine("fogs", bsp.fogs);
    out += recordLine("planes", bsp.planes);
    out += lumpLine("entdata", entities.size(), bsp.entities.size());
    out += "\n";
    out += recordLine("nodes", bsp.nodes);
    out += recordLine("leafs", bsp.leafs);
    out += recordLine("leafsurfaces", bsp.leafSurfaces);
    out += recordLine("leafbrushes", bsp.leafBrushes);
    out += "\n";
    out += recordLine("drawsurfaces", bsp.surfaces, true);
    out += printf9("%9zu   patch surfaces\n", patches);
    out += printf9("%9zu   planar surfaces\n", planar);
    out += printf9("%9zu   trisoup surfaces\n", trisoup);
    if (flares) out += printf9("%9zu   flare surfaces\n", flares);
    if (foliage) out += printf9("%9zu   foliage surfaces\n", foliage);
    out += recordLine("drawverts", bsp.drawVerts, true);
    out += recordLine("drawindexes", bsp.drawIndexes);
    out += "\n";
    out += lumpLine("lightmaps", bsp.lightmaps.size() / bsp::kLightmapPageBytes, bsp.lightmaps.size());
    out += recordLine("lightgrid", bsp.lightGrid, true);
    out += printf9("          visibility    %9zu\n", bsp.visibility.size());
    if (bsp.headerLumps >= 18) out += printf9("          lump 17       %9zu\n", bsp.lump17.size());
    if (bsp.headerLumps >= 19) out += printf9("          lump 18 (SH)  %9zu\n", bsp.shGrid.size());
    out += "\n";

    out += printf9("BSPX lumps: %zu\n", bsp.bspx.size());
    for (const bsp::BspxLump& lump : bsp.bspx) out += printf9("  %-24s %9zu\n", lump.name.c_str(), lump.data.size());

    bool anySh = false;
    if (!bsp.shGrid.empty()) {
        out += shGridSection(bsp.shGrid, "lump 18", name);
        anySh = true;
    }
    if (const bsp::BspxLump* lump = bsp.findBspx(sh::kBspxLumpName)) {
        out += shGridSection(lump->data, std::string("BSPX ") + sh::kBspxLumpName, name);
        anySh = true;
    }
    if (!anySh) out += "SH grid: none\n";
    if (const bsp::BspxLump* lump = bsp.findBspx(sh::kWorldLightsLumpName)) out += worldLightsSection(lump->data, name);
    out += legacyGridSection(bsp, entities);
    out += "---------------------------------\n";
    return out;
}

}  // namespace q3::info
