// _decal entities (q3map2 decals.cpp). A _decal entity holds patches and targets another entity:
// each triangle of a tessellated patch, pushed along the direction from the decal to its target,
// sweeps a prism (the projector). The decal's shader is then laid onto every drawn triangle of a
// model that lies inside a prism and faces it: the piece is clipped to the prism, its texture
// coordinates follow the patch triangle's, and its vertex alpha fades from 255 at the patch to 0
// at the far end. The pieces are Decal surfaces, which -meta merges like faces.
#pragma once

#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"
#include "float_plane.h"

namespace q3 {
class Log;
class ShaderTable;
struct ShaderInfo;
}  // namespace q3

namespace q3::map {
struct MapFile;
}

namespace q3::bspstage {

inline constexpr int kMaxDecalProjectors = 1024;  // q3map2 MAX_PROJECTORS

struct DecalProjector {
    const ShaderInfo* shader = nullptr;
    Vec3 mins, maxs;      // of the prism
    Vec3 center;          // of those bounds
    float radius = 0;     // from the centre to a corner
    int numPlanes = 0;    // front, back, then one per triangle edge
    FPlane planes[6];     // facing out of the prism
    float texMat[2][4] = {};  // s and t: dot(xyz, texMat[i]) + texMat[i][3]
};

// Moves the patches of every _decal entity whose target exists into map.decals, so the entity
// makes no model; warns about decal entities without patches or without a target.
void collectDecalEntities(LoadedMap& map, const map::MapFile& file, Log& log);

// The projectors of map.decals, in entity and patch order (q3map2 ProcessDecals); patches are
// tessellated with the global patch subdivisions. At most kMaxDecalProjectors (warning).
std::vector<DecalProjector> makeDecalProjectors(const LoadedMap& map, const ShaderTable& shaders,
                                                int patchSubdivisions, Log& log);

struct DecalInputs {
    const std::vector<DecalProjector>& projectors;
    const PlaneSet& planes;
    DVec3 entityOrigin;      // the model's origin: projectors are moved into its frame
    int patchSubdivisions = 8;
};

// Appends the Decal surfaces the projectors make on the model's surfaces (q3map2
// MakeEntityDecals), projector by projector; returns how many.
int makeEntityDecals(const DecalInputs& in, std::vector<DrawSurface>& surfaces);

}  // namespace q3::bspstage
