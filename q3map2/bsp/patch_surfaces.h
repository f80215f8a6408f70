// Patches as draw surfaces (q3map2 patch.cpp PatchMapDrawSurfs, surface.cpp DrawSurfaceForMesh): the
// control grid is stored as is (the engine tessellates it); -bsp adds vertex normals, the
// level-of-detail group's bounds and longest curve, and a map plane when the patch is flat.
#pragma once

#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"
#include "patch.h"

namespace q3 {
class Log;
class ShaderTable;
}  // namespace q3

namespace q3::bspstage {

class TerrainShaders;

// Vertex normals of a control grid as q3map2 computes them (MakeMeshNormals): at each point, the
// average of the normals of the triangles it forms with its eight neighbour directions (stepping up
// to three points past coincident ones; rows and columns that close on themselves wrap around).
void makeGridNormals(std::vector<bsp::DrawVert>& verts, int width, int height);
// Moves the approximating (odd) control points onto the curve: columns first, then rows.
void putGridOnCurve(std::vector<bsp::DrawVert>& verts, int width, int height);

// True when every control point lies on one line through the first (q3map2 drops such patches).
bool isDegeneratePatch(const map::MapPatch& patch);

// The longest span along the first row and first column of each 3x3 sub-patch (q3map2's per-patch
// longestCurve, before level-of-detail groups share theirs).
float patchLongestCurve(const map::MapPatch& patch);
// The control points with their texture coordinates, white, without normals.
patch::ControlGrid patchControlGrid(const map::MapPatch& patch);

struct PatchCounts {
    int patches = 0;
    int lodGroups = 0;
};

// Surfaces for the entity's patches in list order. Flat patches get a plane in `planes`. Patches of
// an index-mapped entity with a q3map_indexed shader take their layer shader from `terrain` (none
// when nullptr), layer alphas and height offsets on their control points.
std::vector<DrawSurface> patchSurfaces(const BspEntity& entity, const ShaderTable& shaders, PlaneSet& planes,
                                       const std::vector<EntitySurfaceParams>& paramsByMapEntity, Log& log,
                                       PatchCounts* counts = nullptr, TerrainShaders* terrain = nullptr);

}  // namespace q3::bspstage
