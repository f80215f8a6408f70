// The entity lump -bsp writes (q3map2 bspfile_abstract.cpp UnparseEntities, InjectCommandLine,
// writebsp.cpp SetModelNumbers / SetLightStyles): the .map's entities without func_group,
// group_info, lights (unless kept), misc_model (unless kept), _decal and _skybox; brush entities
// get "model" "*N", origin-brush entities their new "origin", worldspawn the command line.
#pragma once

#include <string>
#include <vector>

#include "bsp_brushes.h"
#include "bspfile.h"

namespace q3::bspstage {

struct EntityLumpOptions {
    std::vector<std::string> stageArgs;  // the -bsp options as given (without the map name)
    std::string version = "2.5.17n";     // _q3map2_version
    bool keepLights = false;             // -keeplights (also sets worldspawn _keepLights)
    bool keepModels = false;             // -keepmodels (also sets worldspawn _keepModels)
    bool recordCommandLine = true;       // false for -onlyents: no _q3map2_cmdline / _q3map2_version
};

// q3map2's _q3map2_cmdline value: the previous value, "; ", then "-bsp" and each argument with
// backslashes, quotes, semicolons and control characters removed.
std::string commandLineValue(const std::string& previous, const std::vector<std::string>& stageArgs);

// Entities in BSP order with their final keys (model numbers follow the entity order).
std::vector<bsp::Entity> bspEntities(const LoadedMap& map, const EntityLumpOptions& options);

}  // namespace q3::bspstage
