// Structural validation of a parsed BSP: every index points at an existing record, every range
// lies inside its lump, geometry is finite, and the raw lumps have consistent headers.
#include "bspfile_internal.h"

#include "sh_grid_lump.h"
#include "world_lights.h"

#include <cmath>

namespace q3::bsp {

namespace {

// Validation context: the file name plus a few message helpers, so each check stays one line.
struct Checker {
    const Bsp& bsp;
    const std::string& name;

    [[noreturn]] void fail(int lump, size_t record, const std::string& what) const {
        detail::failLump(name, lump, "record " + std::to_string(record) + ": " + what);
    }

    // An index into a table of `count` records.
    void index(int lump, size_t record, const char* field, int64_t value, size_t count, const char* target) const {
        if (value < 0 || static_cast<uint64_t>(value) >= count)
            fail(lump, record, std::string(field) + " " + std::to_string(value) + " is out of range (" +
                                   std::to_string(count) + " " + target + ")");
    }

    // A [first, first + num) range inside a table of `count` records; 64-bit so no sum overflows.
    void range(int lump, size_t record, const char* what, int64_t first, int64_t num, size_t count,
               const char* target) const {
        if (first < 0 || num < 0 || static_cast<uint64_t>(first + num) > count)
            fail(lump, record, std::string(what) + " range [" + std::to_string(first) + ", +" + std::to_string(num) +
                                   ") is outside the " + std::to_string(count) + " " + target);
    }

    void finite(int lump, size_t record, const char* field, const float* values, int n) const {
        for (int i = 0; i < n; ++i)
            if (!std::isfinite(values[i]))
                fail(lump, record, std::string(field) + " is not finite (" + std::to_string(values[i]) + ")");
    }
};

// Names are read as C strings everywhere downstream, so each must end inside its 64-byte field.
void checkNames(const Checker& c) {
    for (size_t i = 0; i < c.bsp.shaders.size(); ++i)
        if (std::memchr(c.bsp.shaders[i].name, 0, sizeof c.bsp.shaders[i].name) == nullptr)
            c.fail(LUMP_SHADERS, i, "name is not NUL-terminated within 64 bytes");
    for (size_t i = 0; i < c.bsp.fogs.size(); ++i)
        if (std::memchr(c.bsp.fogs[i].shader, 0, sizeof c.bsp.fogs[i].shader) == nullptr)
            c.fail(LUMP_FOGS, i, "shader name is not NUL-terminated within 64 bytes");
}

void checkPlanes(const Checker& c) {
    for (size_t i = 0; i < c.bsp.planes.size(); ++i) {
        c.finite(LUMP_PLANES, i, "normal", c.bsp.planes[i].normal, 3);
        c.finite(LUMP_PLANES, i, "dist", &c.bsp.planes[i].dist, 1);
    }
}

void checkTree(const Checker& c) {
    const Bsp& b = c.bsp;
    for (size_t i = 0; i < b.nodes.size(); ++i) {
        const Node& n = b.nodes[i];
        c.index(LUMP_NODES, i, "planeNum", n.planeNum, b.planes.size(), "planes");
        for (int side = 0; side < 2; ++side) {
            const int64_t child = n.children[side];
            if (child >= 0) c.index(LUMP_NODES, i, "child node", child, b.nodes.size(), "nodes");
            else c.index(LUMP_NODES, i, "child leaf", -(child + 1), b.leafs.size(), "leafs");
        }
    }
    for (size_t i = 0; i < b.leafs.size(); ++i) {
        const Leaf& l = b.leafs[i];
        c.range(LUMP_LEAFS, i, "leaf surface", l.firstLeafSurface, l.numLeafSurfaces, b.leafSurfaces.size(),
                "leafsurfaces");
        c.range(LUMP_LEAFS, i, "leaf brush", l.firstLeafBrush, l.numLeafBrushes, b.leafBrushes.size(), "leafbrushes");
    }
    for (size_t i = 0; i < b.leafSurfaces.size(); ++i)
        c.index(LUMP_LEAFSURFACES, i, "surface", b.leafSurfaces[i], b.surfaces.size(), "surfaces");
    for (size_t i = 0; i < b.leafBrushes.size(); ++i)
        c.index(LUMP_LEAFBRUSHES, i, "brush", b.leafBrushes[i], b.brushes.size(), "brushes");
}

void checkModelsAndBrushes(const Checker& c) {
    const Bsp& b = c.bsp;
    for (size_t i = 0; i < b.models.size(); ++i) {
        const Model& m = b.models[i];
        c.finite(LUMP_MODELS, i, "mins", m.mins, 3);
        c.finite(LUMP_MODELS, i, "maxs", m.maxs, 3);
        c.range(LUMP_MODELS, i, "surface", m.firstSurface, m.numSurfaces, b.surfaces.size(), "surfaces");
        c.range(LUMP_MODELS, i, "brush", m.firstBrush, m.numBrushes, b.brushes.size(), "brushes");
    }
    for (size_t i = 0; i < b.brushes.size(); ++i) {
        const Brush& br = b.brushes[i];
        c.range(LUMP_BRUSHES, i, "side", br.firstSide, br.numSides, b.brushSides.size(), "brushsides");
        c.index(LUMP_BRUSHES, i, "shaderNum", br.shaderNum, b.shaders.size(), "shaders");
    }
    for (size_t i = 0; i < b.brushSides.size(); ++i) {
        c.index(LUMP_BRUSHSIDES, i, "planeNum", b.brushSides[i].planeNum, b.planes.size(), "planes");
        c.index(LUMP_BRUSHSIDES, i, "shaderNum", b.brushSides[i].shaderNum, b.shaders.size(), "shaders");
    }
    for (size_t i = 0; i < b.fogs.size(); ++i) {
        const Fog& f = b.fogs[i];
        c.index(LUMP_FOGS, i, "brushNum", f.brushNum, b.brushes.size(), "brushes");
        const int32_t sides = b.brushes[static_cast<size_t>(f.brushNum)].numSides;
        if (f.visibleSide < -1 || f.visibleSide >= sides)
            c.fail(LUMP_FOGS, i, "visibleSide " + std::to_string(f.visibleSide) + " is not -1 or one of the " +
                                     std::to_string(sides) + " sides of its brush");
    }
}

void checkSurfaces(const Checker& c) {
    const Bsp& b = c.bsp;
    for (size_t i = 0; i < b.drawVerts.size(); ++i) {
        // Texture and lightmap coordinates are left alone: shipped maps contain NaN lightmap
        // coordinates on vertex-lit surfaces, and nothing geometric depends on them.
        c.finite(LUMP_DRAWVERTS, i, "xyz", b.drawVerts[i].xyz, 3);
        c.finite(LUMP_DRAWVERTS, i, "normal", b.drawVerts[i].normal, 3);
    }
    for (size_t i = 0; i < b.surfaces.size(); ++i) {
        const Surface& s = b.surfaces[i];
        c.index(LUMP_SURFACES, i, "shaderNum", s.shaderNum, b.shaders.size(), "shaders");
        // Old compilers wrote fogNum 0 into maps without any fog; engines never look it up then.
        const bool unusedFog = b.fogs.empty() && s.fogNum == 0;
        if (s.fogNum != -1 && !unusedFog) c.index(LUMP_SURFACES, i, "fogNum", s.fogNum, b.fogs.size(), "fogs");
        // MST_FOLIAGE: q3map2's q3map_foliage surfaces (instanced by Wolfenstein: ET-style engines).
        if (s.surfaceType < MST_BAD || s.surfaceType > MST_FOLIAGE)
            c.fail(LUMP_SURFACES, i, "unknown surfaceType " + std::to_string(s.surfaceType));
        c.range(LUMP_SURFACES, i, "vertex", s.firstVert, s.numVerts, b.drawVerts.size(), "drawverts");
        c.range(LUMP_SURFACES, i, "index", s.firstIndex, s.numIndexes, b.drawIndexes.size(), "drawindexes");
        for (int32_t k = 0; k < s.numIndexes; ++k) {
            const int32_t v = b.drawIndexes[static_cast<size_t>(s.firstIndex + k)];
            if (v < 0 || v >= s.numVerts)
                c.fail(LUMP_SURFACES, i, "index " + std::to_string(s.firstIndex + k) + " = " + std::to_string(v) +
                                             " is outside the surface's " + std::to_string(s.numVerts) + " vertices");
        }
        if ((s.surfaceType == MST_PLANAR || s.surfaceType == MST_TRIANGLE_SOUP || s.surfaceType == MST_FOLIAGE) &&
            s.numIndexes % 3 != 0)
            c.fail(LUMP_SURFACES, i, std::to_string(s.numIndexes) + " indexes do not make whole triangles");
        if (s.surfaceType == MST_PATCH &&
            (s.patchWidth <= 0 || s.patchHeight <= 0 ||
             static_cast<int64_t>(s.patchWidth) * s.patchHeight != s.numVerts))
            c.fail(LUMP_SURFACES, i, "patch size " + std::to_string(s.patchWidth) + "x" +
                                         std::to_string(s.patchHeight) + " does not match its " +
                                         std::to_string(s.numVerts) + " vertices");
        // The model's vertices (patchHeight of them) come first, then one per copy (patchWidth).
        if (s.surfaceType == MST_FOLIAGE &&
            (s.patchWidth < 0 || s.patchHeight < 0 || int64_t(s.patchWidth) + s.patchHeight != s.numVerts))
            c.fail(LUMP_SURFACES, i, "foliage of " + std::to_string(s.patchWidth) + " copies of " +
                                         std::to_string(s.patchHeight) + " vertices does not match its " +
                                         std::to_string(s.numVerts) + " vertices");
    }
}

void checkVisibility(const Checker& c) {
    const std::vector<uint8_t>& vis = c.bsp.visibility;
    if (vis.empty()) return;
    auto fail = [&](const std::string& what) { detail::failLump(c.name, LUMP_VISIBILITY, what); };
    if (vis.size() < 8) fail(std::to_string(vis.size()) + " bytes is shorter than the 8-byte header");
    const int64_t clusters = detail::loadI32(vis.data());
    const int64_t rowBytes = detail::loadI32(vis.data() + 4);
    if (clusters < 0 || rowBytes < 0)
        fail("negative header (numClusters " + std::to_string(clusters) + ", bytesPerCluster " +
             std::to_string(rowBytes) + ")");
    if (rowBytes < (clusters + 7) / 8)
        fail("bytesPerCluster " + std::to_string(rowBytes) + " cannot hold " + std::to_string(clusters) + " clusters");
    if (8 + clusters * rowBytes > static_cast<int64_t>(vis.size()))  // both < 2^31: no overflow
        fail("header claims " + std::to_string(clusters) + " x " + std::to_string(rowBytes) +
             " bytes but the lump holds " + std::to_string(vis.size() - 8));
    for (size_t i = 0; i < c.bsp.leafs.size(); ++i) {
        const int32_t cluster = c.bsp.leafs[i].cluster;
        if (cluster < -1 || cluster >= clusters)
            c.fail(LUMP_LEAFS, i, "cluster " + std::to_string(cluster) + " is out of range (" +
                                      std::to_string(clusters) + " clusters)");
    }
}

void checkShGrid(const std::vector<uint8_t>& lump, const std::string& file, std::string_view where) {
    std::string problem = sh::checkGridLump(lump.data(), lump.size());
    if (problem.empty()) return;
    constexpr std::string_view kCodecPrefix = "SH grid lump: ";
    if (problem.starts_with(kCodecPrefix)) problem.erase(0, kCodecPrefix.size());
    detail::fail(file, where, problem);
}

void checkWorldLights(const std::vector<uint8_t>& lump, const std::string& file) {
    std::string problem = sh::checkWorldLightsLump(lump.data(), lump.size());
    if (problem.empty()) return;
    const std::string prefix = std::string(sh::kWorldLightsLumpName) + ": ";
    if (problem.starts_with(prefix)) problem.erase(0, prefix.size());
    detail::fail(file, std::string("bspx ") + sh::kWorldLightsLumpName, problem);
}

}  // namespace

void validateBsp(const Bsp& bsp, const std::string& name) {
    if (bsp.headerLumps < 17 || bsp.headerLumps > kMaxLumps)
        detail::fail(name, "header", std::to_string(bsp.headerLumps) + " lump entries (expected 17, 18 or 19)");
    if (!bsp.lump17.empty() && bsp.headerLumps < 18)
        detail::failLump(name, LUMP_ADVERTISEMENTS, "has data but the header has only 17 entries");
    if (!bsp.shGrid.empty() && bsp.headerLumps < 19)
        detail::failLump(name, LUMP_LIGHTGRID_SH, "has data but the header has fewer than 19 entries");

    const Checker checker{bsp, name};
    checkNames(checker);
    checkPlanes(checker);
    checkTree(checker);
    checkModelsAndBrushes(checker);
    checkSurfaces(checker);
    checkVisibility(checker);
    if (!bsp.shGrid.empty()) checkShGrid(bsp.shGrid, name, lumpName(LUMP_LIGHTGRID_SH));
    if (const BspxLump* sh = bsp.findBspx(sh::kBspxLumpName))
        checkShGrid(sh->data, name, std::string("bspx ") + sh::kBspxLumpName);
    if (const BspxLump* lights = bsp.findBspx(sh::kWorldLightsLumpName)) checkWorldLights(lights->data, name);
}

}  // namespace q3::bsp
