// Emitting what the world structure knows into BSP lumps (q3map2 writebsp.cpp): planes, the
// shaders of brushes and brush sides, brushes and sides per model, the world tree as nodes and
// leafs with their leaf brush lists, one leaf per brush model, models and the entity lump.
//
// Without draw surfaces (no leaf surfaces, verts, indexes, fogs) the result is not a loadable map:
// the -bsp stage adds them (bsp_stage.h); this structure-only form serves the developer tool and
// the structure tests.
#pragma once

#include "bsp_brushes.h"
#include "bspfile.h"
#include "entity_lump.h"
#include "world_structure.h"

namespace q3 {
class ShaderTable;
}

namespace q3::bspstage {

// A brush model's tree: one open leaf (cluster 0, area 0) holding every brush of the entity.
Tree singleLeafTree(const BspEntity& entity);

// Filters the world's detail brushes into `world.tree` (leaf brush lists) and writes the lumps
// above. Leaf 0 is q3map2's reserved dummy; nodes are written pre-order, front child first.
bsp::Bsp emitStructure(LoadedMap& map, WorldStructure& world, const ShaderTable& shaders,
                       const EntityLumpOptions& entityOptions);

}  // namespace q3::bspstage
