// -patchmeta (q3map2 surface_meta.cpp TriangulatePatchSurface): a patch becomes a triangle
// surface tessellated as -light meshes it (iterations from its longest curve and the patch
// subdivisions, divided by the entity's _patchQuality, or from _patchSubdivide; points on the
// curve; straight rows and columns removed), each grid quad two triangles with alternating
// diagonals.
#pragma once

#include "draw_surface.h"
#include "patch.h"

namespace q3::map {
struct MapEntity;
}

namespace q3::bspstage::meta {

// A patch surface's control points as a grid (position, normal, texture and lightmap coordinates,
// colour).
patch::ControlGrid surfaceControlGrid(const DrawSurface& patch);

// A vertex of a tessellated patch as a draw vertex (colour rounded to bytes).
bsp::DrawVert drawVert(const patch::PatchVertex& p);
// A vertex grid (row-major) as a mesh with its triangles (alternating diagonals).
patch::PatchMesh asPatchMesh(const std::vector<bsp::DrawVert>& verts, int width, int height);

// The tessellated copy of a patch surface (kind Meta, same shader, fog and lighting keys).
DrawSurface patchMetaSurface(const DrawSurface& patch, const map::MapEntity& entity, int patchSubdivisions);

// Whether the patch itself stays for collision once tessellated: only solid or playerclip ones.
bool keepsCollisionPatch(const ShaderInfo& shader);

}  // namespace q3::bspstage::meta
