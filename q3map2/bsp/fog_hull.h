// Worldspawn "_foghull" (q3map2 surface.cpp MakeFogHullSurfs): a box 128 units outside the world
// brushes' bounds, drawn with the named sky shader from every open leaf, so that distance fog has
// something to end on.
#pragma once

#include <optional>
#include <string>

#include "draw_surface.h"
#include "dvec3.h"
#include "shader_info.h"

namespace q3::bspstage {

// The hull surface for a "_foghull" value (the shader, without "textures/"), or nothing when the
// value is empty.
std::optional<DrawSurface> fogHullSurface(const std::string& value, const DBounds& worldBounds,
                                          const ShaderTable& shaders);

}  // namespace q3::bspstage
