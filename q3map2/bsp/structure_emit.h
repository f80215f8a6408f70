// Emitting what the world structure knows into BSP lumps (q3map2 writebsp.cpp): planes, the
// shaders of brushes and brush sides, brushes and sides per model, the world tree as nodes and
// leafs with their leaf brush lists, one leaf per brush model, models and the entity lump.
//
// Not a loadable map yet: there are no draw surfaces (no leaf surfaces, verts, indexes, fogs), so
// nothing here is reachable from the command line.
#pragma once

#include "bsp_brushes.h"
#include "bspfile.h"
#include "entity_lump.h"
#include "world_structure.h"

namespace q3 {
class ShaderTable;
}

namespace q3::bspstage {

// Filters the world's detail brushes into `world.tree` (leaf brush lists) and writes the lumps
// above. Leaf 0 is q3map2's reserved dummy; nodes are written pre-order, front child first.
bsp::Bsp emitStructure(LoadedMap& map, WorldStructure& world, const ShaderTable& shaders,
                       const EntityLumpOptions& entityOptions);

}  // namespace q3::bspstage
