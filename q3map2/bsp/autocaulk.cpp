#include "autocaulk.h"

#include <algorithm>

namespace q3::bspstage {
namespace {

char sideLetter(const Brush& brush, const BrushSide& side, bool globalFog, bool nodrawIsSolid) {
    if (!side.visibleHull.empty() || (side.compileFlags & compileflags::NoDraw) || globalFog) return '-';
    const ShaderInfo& content = *brush.contentShader;
    if (content.compileFlags & compileflags::Liquid) {
        if (content.contentFlags & contents::Lava) return 'l';
        if (content.contentFlags & contents::Slime) return 's';
        return 'w';
    }
    if (brush.compileFlags & compileflags::Translucent) {
        // Many games' nodraw is nonsolid: then a solid translucent brush falls back to caulk.
        if (content.compileFlags & compileflags::Solid) return nodrawIsSolid ? 'N' : 'c';
        return 'n';
    }
    return 'c';
}

}  // namespace

std::string autocaulkText(const std::vector<Brush>& worldBrushes, const ShaderTable& shaders) {
    const bool nodrawIsSolid = (shaders.find("textures/common/nodraw").compileFlags & compileflags::Solid) != 0;
    std::string text;
    for (const Brush& brush : worldBrushes) {
        text += std::to_string(brush.brushNum) + ' ';
        // A fog volume nobody sees from the inside is the map's global fog: left alone.
        const bool globalFog =
            brush.contentShader && (brush.contentShader->compileFlags & compileflags::Fog) &&
            std::all_of(brush.sides.begin(), brush.sides.end(), [](const BrushSide& s) { return s.visibleHull.empty(); });
        for (const BrushSide& side : brush.sides) text += sideLetter(brush, side, globalFog, nodrawIsSolid);
        text += '\n';
    }
    return text;
}

}  // namespace q3::bspstage
