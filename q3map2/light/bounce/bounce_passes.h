// The -bounce loop's emitters: each radiosity pass turns the light the previous pass left on every
// lightmapped surface (per style) into area lights (bounce_lights.h), placed in the PVS like the
// map's own lights; -dump writes each pass's emitters as <map>_bounce_NNN.map.
#pragma once

#include <vector>

#include "grid_sh_gather.h"
#include "lights.h"

namespace q3 {
class Log;
}

namespace q3::light {

struct LightContext;
struct SurfaceLight;

class BouncePasses {
public:
    // `albedo`: per BSP shader (shaderAlbedo), kept alive by the caller.
    BouncePasses(const LightContext& ctx, const std::vector<ShaderAlbedo>& albedo, Log& log);
    // The emitters of bounce number `bounce` (1-based) from the light of the previous pass, less
    // `ambient` (the world ambient is not re-emitted, as in q3map2).
    std::vector<Light> emitters(const std::vector<SurfaceLight>& previous, int bounce, Vec3 ambient);

private:
    const LightContext& ctx_;
    Log& log_;
    const std::vector<ShaderAlbedo>& albedo_;  // per BSP shader
};

}  // namespace q3::light
