// The Quake 3 surfaceparm table (q3map2 game_quake3.h): each parm clears some flags, then sets
// others, on the content, surface and compile flag words.
#include <array>

#include "script.h"
#include "shader_info.h"

namespace q3 {
namespace {

namespace c = contents;
namespace s = surfaceflags;
namespace k = compileflags;

constexpr std::array kSurfaceParms = {
    // name, contents, contentsClear, surface, surfaceClear, compile, compileClear
    SurfaceParm{"default", c::Solid, ~0u, 0, ~0u, k::Solid, ~0u},
    SurfaceParm{"lightgrid", 0, 0, 0, 0, k::LightGrid, 0},
    SurfaceParm{"antiportal", 0, 0, 0, 0, k::AntiPortal, 0},
    SurfaceParm{"skip", 0, 0, 0, 0, k::Skip, 0},
    SurfaceParm{"origin", c::Origin, c::Solid, 0, 0, k::Origin | k::Translucent, k::Solid},
    SurfaceParm{"areaportal", c::AreaPortal, c::Solid, 0, 0, k::AreaPortal | k::Translucent, k::Solid},
    SurfaceParm{"trans", c::Translucent, 0, 0, 0, k::Translucent, 0},
    SurfaceParm{"detail", c::Detail, 0, 0, 0, k::Detail, 0},
    SurfaceParm{"structural", c::Structural, 0, 0, 0, k::Structural, 0},
    SurfaceParm{"hint", 0, 0, s::Hint, 0, k::Hint, 0},
    SurfaceParm{"nodraw", 0, 0, s::NoDraw, 0, k::NoDraw, 0},
    SurfaceParm{"alphashadow", 0, 0, s::AlphaShadow, 0, k::AlphaShadow | k::Translucent, 0},
    SurfaceParm{"lightfilter", 0, 0, s::LightFilter, 0, k::LightFilter | k::Translucent, 0},
    SurfaceParm{"nolightmap", 0, 0, s::VertexLit, 0, k::VertexLit, 0},
    SurfaceParm{"pointlight", 0, 0, s::VertexLit, 0, k::VertexLit, 0},
    SurfaceParm{"nonsolid", 0, c::Solid, s::NonSolid, 0, 0, k::Solid},
    SurfaceParm{"trigger", c::Trigger, c::Solid, 0, 0, k::Translucent, k::Solid},
    SurfaceParm{"water", c::Water, c::Solid, 0, 0, k::Liquid | k::Translucent, k::Solid},
    SurfaceParm{"slime", c::Slime, c::Solid, 0, 0, k::Liquid | k::Translucent, k::Solid},
    SurfaceParm{"lava", c::Lava, c::Solid, 0, 0, k::Liquid | k::Translucent, k::Solid},
    SurfaceParm{"playerclip", c::PlayerClip, c::Solid, 0, 0, k::Detail | k::Translucent, k::Solid},
    SurfaceParm{"monsterclip", c::MonsterClip, c::Solid, 0, 0, k::Detail | k::Translucent, k::Solid},
    SurfaceParm{"nodrop", c::NoDrop, c::Solid, 0, 0, k::Translucent, k::Solid},
    SurfaceParm{"clusterportal", c::ClusterPortal, c::Solid, 0, 0, k::Translucent, k::Solid},
    SurfaceParm{"donotenter", c::DoNotEnter, c::Solid, 0, 0, k::Translucent, k::Solid},
    SurfaceParm{"botclip", c::BotClip, c::Solid, 0, 0, k::Translucent, k::Solid},
    SurfaceParm{"fog", c::Fog, c::Solid, 0, 0, k::Fog, k::Solid},
    SurfaceParm{"sky", 0, 0, s::Sky, 0, k::Sky, 0},
    SurfaceParm{"slick", 0, 0, s::Slick, 0, 0, 0},
    SurfaceParm{"noimpact", 0, 0, s::NoImpact, 0, 0, 0},
    SurfaceParm{"nomarks", 0, 0, s::NoMarks, 0, k::NoMarks, 0},
    SurfaceParm{"ladder", 0, 0, s::Ladder, 0, 0, 0},
    SurfaceParm{"nodamage", 0, 0, s::NoDamage, 0, 0, 0},
    SurfaceParm{"metalsteps", 0, 0, s::MetalSteps, 0, 0, 0},
    SurfaceParm{"flesh", 0, 0, s::Flesh, 0, 0, 0},
    SurfaceParm{"nosteps", 0, 0, s::NoSteps, 0, 0, 0},
    SurfaceParm{"nodlight", 0, 0, s::NoDLight, 0, 0, 0},
    SurfaceParm{"dust", 0, 0, s::Dust, 0, 0, 0},
    SurfaceParm{"noob", 0, 0, s::NoOb, 0, 0, 0},
    SurfaceParm{"ob", 0, 0, 0, 0, k::Ob, 0},
};

}  // namespace

const SurfaceParm* findSurfaceParm(std::string_view name) {
    for (const SurfaceParm& parm : kSurfaceParms)
        if (equalsNoCase(parm.name, name)) return &parm;
    return nullptr;
}

void applySurfaceParm(const SurfaceParm& parm, ShaderInfo& shader) {
    shader.contentFlags = (shader.contentFlags & ~parm.contentsClear) | parm.contents;
    shader.surfaceFlags = (shader.surfaceFlags & ~parm.surfaceClear) | parm.surface;
    shader.compileFlags = (shader.compileFlags & ~parm.compileClear) | parm.compile;
}

bool applySurfaceParm(std::string_view name, ShaderInfo& shader) {
    const SurfaceParm* parm = findSurfaceParm(name);
    if (!parm) return false;
    applySurfaceParm(*parm, shader);
    return true;
}

}  // namespace q3
