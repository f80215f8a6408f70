// Surface flags the command line adds to every shader written to the BSP (-noob, -globalflag).
// q3map2 applies them when a shader is finished, so they reach every shader entry, including
// "noshader" and the flags brush bevels inherit from their sides.
#pragma once

#include <cstdint>
#include <string_view>

#include "shader_info.h"

namespace q3::bspstage {

struct ShaderFlagRules {
    bool noOb = false;                // -noob: every shader without surfaceparm ob gets noob
    uint32_t globalSurfaceFlags = 0;  // -globalflag: ORed into every shader

    uint32_t surfaceFlags(const ShaderInfo& shader) const {
        uint32_t flags = shader.surfaceFlags;
        if (noOb && !(shader.compileFlags & compileflags::Ob)) flags |= surfaceflags::NoOb;
        return flags | globalSurfaceFlags;
    }

    // Folds one surfaceparm's surface flags (clear, then set) into the global flags. False when
    // the name is not a surfaceparm.
    bool addGlobalFlag(std::string_view parmName) {
        const SurfaceParm* parm = findSurfaceParm(parmName);
        if (!parm) return false;
        globalSurfaceFlags = (globalSurfaceFlags & ~parm->surfaceClear) | parm->surface;
        return true;
    }
};

}  // namespace q3::bspstage
