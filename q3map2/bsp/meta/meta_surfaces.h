// -meta for one model's surfaces (q3map2 surface_meta.cpp MakeEntityMetaTriangles,
// SmoothMetaTriangles, MergeMetaTriangles; FixMetaTJunctions is compiled out there and so is
// absent here). With -meta, or for shaders with q3map_forceMeta, brush faces are triangulated (by
// strips, or -maxarea) and become meta triangles, as do forced-meta surfaces and, with -patchmeta
// or the entity key _patchMeta, patches tessellated like -light's mesh; autosprite shaders and
// misc_model triangle soups stay as they are. The triangles are smoothed and merged into new
// surfaces appended to the model's list, in place of the ones they came from.
#pragma once

#include <vector>

#include "draw_surface.h"
#include "libc_random.h"
#include "meta_merge.h"
#include "surface_classify.h"
#include "texture_sizes.h"

namespace q3 {
class Log;
namespace map {
struct MapEntity;
}
}  // namespace q3

namespace q3::bspstage::meta {

struct MetaOptions {
    bool meta = false;       // -meta
    bool patchMeta = false;  // -patchmeta
    bool maxArea = false;    // -maxarea: faces triangulated by largest area
    int patchSubdivisions = 8;
    MergeLimits limits;
};

struct MetaCounts {
    int metaSurfaces = 0;  // surfaces turned into meta triangles
    int stripped = 0;
    int fanned = 0;
    int maxArea = 0;
    int patchMeta = 0;
    int metaVerts = 0;
    int metaTriangles = 0;
    int smoothed = 0;
    MergeCounts merged;
};

struct MetaInputs {
    const map::MapEntity& entity;  // its _patchMeta, _patchQuality, _patchSubdivide keys
    PlaneSet& planes;
    const TextureSizes& textures;
    const ClassifyOptions& classify;
    LibcRandom& random;  // -maxarea retries, drawn in surface order
    const ShaderTable* shaders = nullptr;  // orders merged surfaces by shader load order
};

// Replaces the model's meta-bound surfaces by merged meta surfaces (appended); emptied ones are
// removed. Returns the counters q3map2 prints.
MetaCounts makeMetaSurfaces(std::vector<DrawSurface>& surfaces, const MetaInputs& in, const MetaOptions& options,
                            Log& log);

// Whether patches of this entity are tessellated into meta triangles (-patchmeta or _patchMeta).
bool patchMetaFor(const map::MapEntity& entity, const MetaOptions& options);

// With -patchmeta (or _patchMeta) every patch left for collision is written nodraw and pointlight,
// without lightmap projection, whether or not it was tessellated (q3map2 EmitPatchSurface).
void markPatchCollision(std::vector<DrawSurface>& surfaces, const map::MapEntity& entity, const MetaOptions& options);

}  // namespace q3::bspstage::meta
