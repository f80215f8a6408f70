// Surfaces a shader or entity asks to be copied (q3map2 surface.cpp FinishSurface, CloneSurface,
// MakeCelSurface): q3map_cloneShader adds a copy drawn with that shader, q3map_backShader a copy
// with that shader facing the other way, and a cel shader (the entity's _celshader, else
// worldspawn's, else -celshader) a non-planar copy of every surface whose shader is neither
// translucent nor sky. Copies come after the originals, are finished in turn (a back copy makes
// no further copies), and belong to no brush side.
#pragma once

#include <string>
#include <vector>

#include "draw_surface.h"

namespace q3 {
class ShaderTable;
namespace map {
struct MapFile;
}
}  // namespace q3

namespace q3::bspstage {

struct FinishInputs {
    const map::MapFile& file;    // entity keys (_celshader) by .map entity number
    const ShaderTable& shaders;
    std::string globalCelShader;  // -celshader, with "textures/" in front; empty: none
    int maxSurfaces;              // -maxmapdrawsurfs: shaders that clone each other stop here
};

// Appends the copies to `surfaces`; returns how many were added. Throws CompileError when the
// copies pass `maxSurfaces` (shaders cloning each other in a circle).
int finishSurfaces(std::vector<DrawSurface>& surfaces, const FinishInputs& in);

// q3map2 TCMod: the shader's q3map_tcMod applied to every texture coordinate of the surface.
void applyTcMod(DrawSurface& ds);

}  // namespace q3::bspstage
