// Surfaces a shader or entity asks to be copied (q3map2 surface.cpp FinishSurface, CloneSurface,
// MakeCelSurface): q3map_cloneShader adds a copy drawn with that shader, q3map_backShader a copy
// with that shader facing the other way, and a cel shader (the entity's _celshader, else
// worldspawn's, else -celshader) a non-planar copy of every surface whose shader is neither
// translucent nor sky. Copies come after the originals, are finished in turn (a back copy makes
// no further copies), and belong to no brush side.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "bsp_brushes.h"
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

// q3map2 ColorMod: `mods` (a shader's q3map_colorGen/colorMod/rgbGen/rgbMod/alphaGen/alphaMod steps,
// in order) applied to one vertex colour; the second form to every vertex of the surface with its
// shader's steps.
void applyColorMods(std::span<const ShaderColorMod> mods, bsp::DrawVert& v);
void applyColorMods(DrawSurface& ds);

// q3map2 VolumeColorMods: brushes whose shader's first colorMod step is `volume` apply the shader's
// steps to the vertexes of `ds` they hold (within one unit of every side). colorModVolumes lists an
// entity's such brushes (func_group ones included, in the entity's brush order).
std::vector<const Brush*> colorModVolumes(const BspEntity& entity);
void applyVolumeColorMods(DrawSurface& ds, std::span<const Brush* const> volumes, const PlaneSet& planes);

}  // namespace q3::bspstage
