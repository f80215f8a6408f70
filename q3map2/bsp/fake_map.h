// -fakemap (q3map2 map.cpp LoadMapFile, brush.cpp WriteBSPBrushMap): the world brushes, bevels
// included, as a .map of three-point planes with "notexture", for inspecting what the compiler
// made of the map.
#pragma once

#include <string>
#include <vector>

#include "bsp_brushes.h"

namespace q3::bspstage {

// The text of fakemap.map: each side's plane as three corners of its huge base winding, cut to
// integers.
std::string fakeMapText(const std::vector<Brush>& worldBrushes, const PlaneSet& planes);

}  // namespace q3::bspstage
