// The "model" keys of brush entities (q3map2 bsp.cpp SetCloneModelNumbers, writebsp.cpp
// SetModelNumbers): every entity past the world with brushes or patches gets "*1", "*2", ... in
// entity order. A clone ("_clone", "_ins" or "_instance" naming another entity's "_clonename")
// takes that entity's model instead and loses its own brushes and patches, so the game draws the
// same model at the clone's origin.
#pragma once

#include "bsp_brushes.h"
#include "log.h"

namespace q3::bspstage {

// Sets BspEntity::model for the whole map. `resolveClones` false (-onlyents) numbers clones like
// any other entity and keeps their brushes.
void numberModels(LoadedMap& map, bool resolveClones, Log& log);

}  // namespace q3::bspstage
