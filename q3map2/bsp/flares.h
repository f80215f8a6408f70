// Flare surfaces with -flares (q3map2 surface.cpp DrawSurfaceForFlare, AddSurfaceFlare; bsp.cpp
// ProcessWorldModel): a corona for every `light` entity with _flare or _flareshader (pointing at its
// target, else down), and one at the centre of every surface whose shader has q3map_flare, pushed
// two units off it along its plane normal, with the shader's light colour.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include "draw_surface.h"

namespace q3 {
class Log;
class ShaderTable;
class Vfs;
struct ShaderInfo;
}  // namespace q3

namespace q3::map {
struct MapFile;
}

namespace q3::bspstage {

// The colour a shader gives its flares: q3map_lightRGB, else the average colour of its light image
// scaled so that its largest component is 1 (white without an image).
class FlareColors {
public:
    static FlareColors load(const std::vector<const ShaderInfo*>& shaders, const Vfs* vfs, Log& log);
    Vec3 of(const ShaderInfo& shader) const;

private:
    std::map<const ShaderInfo*, Vec3> colors_;
};

// The flare shader a flare uses: the one named, else quake3's "flareshader".
const ShaderInfo& flareShader(const ShaderTable& shaders, const std::string& name);

// Flares of the map's light entities (world only).
std::vector<DrawSurface> lightFlares(const map::MapFile& file, const ShaderTable& shaders);

// The flare of a surface whose shader has q3map_flare, or nothing.
std::optional<DrawSurface> surfaceFlare(const DrawSurface& ds, const DVec3& entityOrigin, const ShaderTable& shaders,
                                        const FlareColors& colors);

}  // namespace q3::bspstage
