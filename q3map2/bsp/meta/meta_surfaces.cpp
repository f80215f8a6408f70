#include "meta_surfaces.h"

#include <cstdlib>

#include "count_line.h"
#include "face_subdivide.h"
#include "log.h"
#include "map_file.h"
#include "max_area_triangles.h"
#include "meta_smooth.h"
#include "patch_meta.h"
#include "shader_info.h"
#include "surface_triangles.h"

namespace q3::bspstage::meta {
namespace {

void clearSurface(DrawSurface& ds) {
    ds.kind = SurfaceKind::Bad;
    ds.planar = false;
    ds.planeNum = -1;
    ds.verts.clear();
    ds.indexes.clear();
    ds.tjunctionVerts.clear();
}

// Surface flags of a shader with one more surfaceparm applied.
uint32_t withParm(uint32_t flags, const char* name) {
    const SurfaceParm* parm = findSurfaceParm(name);
    return parm ? (flags & ~parm->surfaceClear) | parm->surface : flags;
}

}  // namespace

bool patchMetaFor(const map::MapEntity& entity, const MetaOptions& options) {
    if (options.patchMeta) return true;
    const std::string* v = entity.find("_patchMeta");
    if (!v) v = entity.find("patchMeta");
    return v && std::atoi(v->c_str()) != 0;
}

void markPatchCollision(std::vector<DrawSurface>& surfaces, const map::MapEntity& entity, const MetaOptions& options) {
    if (!patchMetaFor(entity, options)) return;
    for (DrawSurface& ds : surfaces) {
        if (ds.kind != SurfaceKind::Patch || ds.verts.empty()) continue;
        ds.extraSurfaceFlags = withParm(withParm(0, "nodraw"), "pointlight");
        ds.planeNormal = {0, 0, 0};
        ds.lightmapAxis = {0, 0, 0};
        ds.sampleSize = 0;
    }
}

MetaCounts makeMetaSurfaces(std::vector<DrawSurface>& surfaces, const MetaInputs& in, const MetaOptions& options,
                            Log& log) {
    MetaCounts counts;
    MetaTriangles set;
    TriangulationCounts triangulated;
    const bool patches = patchMetaFor(in.entity, options);
    // Tessellated patches are appended and reach the end of this walk too.
    for (size_t i = 0; i < surfaces.size(); ++i) {
        DrawSurface& ds = surfaces[i];
        if (ds.verts.empty() || ds.shader->autosprite) continue;
        if (!options.meta && !ds.shader->forceMeta) continue;
        switch (ds.kind) {
            case SurfaceKind::Face:
            case SurfaceKind::Decal:
                if (options.maxArea)
                    triangulateFaceByMaxArea(ds, in.random, &triangulated);
                else
                    triangulateFace(ds, &triangulated);
                classifySurface(ds, in.planes, in.classify);
                set.addSurface(ds, int(i), in.planes, log);
                ++counts.metaSurfaces;
                clearSurface(ds);
                break;
            case SurfaceKind::Patch: {
                if (!patches) break;
                DrawSurface tessellated = patchMetaSurface(ds, in.entity, options.patchSubdivisions);
                if (!keepsCollisionPatch(*ds.shader)) clearSurface(ds);
                classifySurface(tessellated, in.planes, in.classify);
                surfaces.push_back(std::move(tessellated));
                ++counts.patchMeta;
                break;
            }
            case SurfaceKind::ForcedMeta:
            case SurfaceKind::Meta:
                set.addSurface(ds, int(i), in.planes, log);
                ++counts.metaSurfaces;
                clearSurface(ds);
                break;
            default:
                break;
        }
    }
    counts.stripped = triangulated.strips;
    counts.fanned = triangulated.fans;
    counts.maxArea = triangulated.maxArea;
    counts.metaVerts = int(set.groups.size());  // q3map2 counts positions
    counts.metaTriangles = int(set.triangles.size());
    tidySurfaces(surfaces);

    counts.smoothed = smoothMetaTriangles(set, options.limits.npDegrees);
    std::vector<DrawSurface> merged = mergeMetaTriangles(set, in.planes, in.textures, options.limits, &counts.merged, in.shaders);
    for (DrawSurface& ds : merged) {
        // Classification would take the axis from vertex normals, which smoothing may have bent:
        // the seed triangle's axis, which decided the merge, is kept.
        const Vec3 axis = ds.lightmapAxis;
        classifySurface(ds, in.planes, in.classify);
        ds.lightmapAxis = axis;
        surfaces.push_back(std::move(ds));
    }
    return counts;
}

}  // namespace q3::bspstage::meta
