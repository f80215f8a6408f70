// Brush faces as draw surfaces (q3map2 surface.cpp CullSides, ClipSidesIntoTree, DrawSurfaceForSide):
// sides hidden inside other brushes or behind a coincident face are culled, every other visible side
// becomes a face surface from its visible hull, with vertices snapped to 1/8 unit and texture
// coordinates from the side's projection.
#pragma once

#include <memory>

#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"
#include "texture_sizes.h"
#include "winding.h"

namespace q3::bspstage {

class TerrainShaders;

struct CullCounts {
    int hidden = 0;      // sides inside another brush
    int coincident = 0;  // sides facing another side with the same winding
};

// Marks the culled sides of one entity's brushes.
CullCounts cullSides(std::vector<Brush>& brushes, const PlaneSet& planes);

// What face surfaces are made with.
struct FaceContext {
    const PlaneSet& planes;
    const TextureSizes& textures;
    bool brushSnap = true;  // round vertices to 1/8 unit (off with -nobrushsnap)
    // -skyfix: the shaders to find the sky box images in, and the surfaces of earlier models
    // (a shader-only surface is made once per shader in the whole BSP).
    const ShaderTable* skyFixShaders = nullptr;
    const std::vector<std::unique_ptr<DrawSurface>>* earlierSurfaces = nullptr;
    TerrainShaders* terrain = nullptr;  // layer shaders of index-mapped entities; nullptr: none layered
};

// The lighting keys of a .map entity; `worldGroup` for the world and func_groups.
EntitySurfaceParams entitySurfaceParams(const map::MapEntity& entity, bool worldGroup);
// Those of every entity of the file, by entity number.
std::vector<EntitySurfaceParams> entitySurfaceParams(const map::MapFile& map);

// The face surface of `winding` on side `sideIndex` of brush `brushIndex` of `entity`; its lighting
// keys come from `params`. `backFace`: the reversed copy a fog side gets, on the flipped plane.
DrawSurface faceSurface(const BspEntity& entity, int brushIndex, int sideIndex, const Winding& winding,
                        const EntitySurfaceParams& params, const FaceContext& context, bool backFace = false);

// Face surfaces of every side with a visible hull (after clipSidesIntoTree), in brush and side order:
// none for culled sides and nodraw shaders (fog and q3map_indexed excepted); autosprite and
// q3map_noClip faces use the whole winding; fog faces get a reversed copy too. `paramsByMapEntity` holds the lighting keys of
// every .map entity, by entity number.
void addFaceSurfaces(const BspEntity& entity, const FaceContext& context,
                     const std::vector<EntitySurfaceParams>& paramsByMapEntity, std::vector<DrawSurface>& out);

}  // namespace q3::bspstage
