#include "patch_meta.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "map_file.h"
#include "patch.h"
#include "shader_info.h"

namespace q3::bspstage::meta {
namespace {

const std::string* firstKey(const map::MapEntity& e, std::initializer_list<const char*> keys) {
    for (const char* k : keys)
        if (const std::string* v = e.find(k)) return v;
    return nullptr;
}

}  // namespace

patch::ControlGrid surfaceControlGrid(const DrawSurface& ds) {
    patch::ControlGrid grid;
    grid.width = ds.patchWidth;
    grid.height = ds.patchHeight;
    grid.points.reserve(ds.verts.size());
    for (const bsp::DrawVert& v : ds.verts) {
        patch::PatchVertex p;
        p.xyz = xyzOf(v);
        p.normal = normalOf(v);
        for (int i = 0; i < 2; ++i) {
            p.st[i] = v.st[i];
            p.lightmap[i] = v.lightmap[i];
        }
        for (int i = 0; i < 4; ++i) p.color[i] = float(v.color[i]);
        grid.points.push_back(p);
    }
    return grid;
}

bsp::DrawVert drawVert(const patch::PatchVertex& p) {
    bsp::DrawVert v{};
    p.xyz.toArray(v.xyz);
    p.normal.toArray(v.normal);
    for (int i = 0; i < 2; ++i) {
        v.st[i] = p.st[i];
        v.lightmap[i] = p.lightmap[i];
    }
    for (int i = 0; i < 4; ++i) v.color[i] = uint8_t(std::clamp(std::lround(p.color[i]), 0L, 255L));
    return v;
}

patch::PatchMesh asPatchMesh(const std::vector<bsp::DrawVert>& verts, int width, int height) {
    DrawSurface grid;
    grid.patchWidth = width;
    grid.patchHeight = height;
    grid.verts = verts;
    patch::ControlGrid g = surfaceControlGrid(grid);
    patch::PatchMesh mesh;
    mesh.width = width;
    mesh.height = height;
    mesh.verts = std::move(g.points);
    patch::triangulateGrid(mesh);
    return mesh;
}

DrawSurface patchMetaSurface(const DrawSurface& patchSurface, const map::MapEntity& entity, int patchSubdivisions) {
    int subdivisions;
    if (const std::string* s = firstKey(entity, {"_patchSubdivide", "patchSubdivide"})) {
        subdivisions = std::atoi(s->c_str());
    } else {
        const std::string* q = firstKey(entity, {"_patchQuality", "patchQuality"});
        const int quality = q ? std::atoi(q->c_str()) : 0;
        subdivisions = patchSubdivisions / (quality == 0 ? 1 : quality);
    }
    const patch::PatchMesh mesh =
        patch::tessellateForLighting(surfaceControlGrid(patchSurface), patchSurface.longestCurve, subdivisions);

    DrawSurface ds = patchSurface;
    ds.kind = SurfaceKind::Meta;
    ds.patchWidth = ds.patchHeight = 0;
    ds.verts.clear();
    ds.verts.reserve(mesh.verts.size());
    for (const patch::PatchVertex& p : mesh.verts) ds.verts.push_back(drawVert(p));
    ds.indexes.assign(mesh.indices.begin(), mesh.indices.end());
    return ds;
}

bool keepsCollisionPatch(const ShaderInfo& shader) {
    return (shader.compileFlags & compileflags::Solid) != 0 || (shader.contentFlags & contents::PlayerClip) != 0;
}

}  // namespace q3::bspstage::meta
