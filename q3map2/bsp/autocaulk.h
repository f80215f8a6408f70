// -autocaulk (q3map2 bsp.cpp autocaulk_write): for NetRadiant's autocaulk tool, one line per world
// brush, its map primitive number, then one letter per side saying what the side could become:
// '-' keep (seen from the inside, or already nodraw), 'c' caulk, 'N' nodraw, 'n' nonsolid nodraw,
// 'w'/'s'/'l' water/slime/lava caulk. The compile stops after it (no BSP, no .prt).
#pragma once

#include <string>
#include <vector>

#include "bsp_brushes.h"
#include "shader_info.h"

namespace q3::bspstage {

// The .caulk text for the world brushes, once their visible hulls are known.
std::string autocaulkText(const std::vector<Brush>& worldBrushes, const ShaderTable& shaders);

}  // namespace q3::bspstage
