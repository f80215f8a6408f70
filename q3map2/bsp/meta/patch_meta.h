// -patchmeta (q3map2 surface_meta.cpp TriangulatePatchSurface): a patch becomes a triangle
// surface tessellated as -light meshes it (iterations from its longest curve and the patch
// subdivisions, divided by the entity's _patchQuality, or from _patchSubdivide; points on the
// curve; straight rows and columns removed), each grid quad two triangles with alternating
// diagonals.
#pragma once

#include "draw_surface.h"

namespace q3::map {
struct MapEntity;
}

namespace q3::bspstage::meta {

// The tessellated copy of a patch surface (kind Meta, same shader, fog and lighting keys).
DrawSurface patchMetaSurface(const DrawSurface& patch, const map::MapEntity& entity, int patchSubdivisions);

// Whether the patch itself stays for collision once tessellated: only solid or playerclip ones.
bool keepsCollisionPatch(const ShaderInfo& shader);

}  // namespace q3::bspstage::meta
