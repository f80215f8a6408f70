// The shaders indexed terrain surfaces take (q3map2 GetIndexedShader, FinishShader): a layer shader
// found by name adopts a few properties of the surface's own shader, and a q3map_terrain shader
// without q3map_tcGen projects its texture from above, one image over twice its pixel size.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "shader_info.h"
#include "texture_sizes.h"
#include "vec3.h"

namespace q3 {
class Log;
class Vfs;
}  // namespace q3

namespace q3::bspstage {

struct LoadedMap;

// A texture projection from world positions: st = (dot(s, p), dot(t, p)).
struct GeneratedProjection {
    Vec3 s{0, 0, 0};
    Vec3 t{0, 0, 0};
};

// q3map_tcGen's vectors, or q3map_terrain's top-down projection over the texture size; nullopt
// when the shader's faces keep the map's projection.
std::optional<GeneratedProjection> generatedProjection(const ShaderInfo& shader, TextureSize size);

// The layer shaders of one compile. q3map2 changes the layer shader itself, so every surface
// using it sees what all its parents gave it; here each layer shader is one copy shared by every
// indexed surface (a surface naming the layer shader directly keeps the script's).
class TerrainShaders {
public:
    // `sizes` receives the texture size of each layer shader copy (for texturing and meta merging);
    // implicit layer shaders are written as `map` spells them. `vfs` may be null (no image sizes).
    TerrainShaders(const ShaderTable& table, TextureSizes& sizes, const Vfs* vfs, LoadedMap& map, Log& log);

    // The layer shader `name` after adopting `parent`'s global texture, forced meta, non-planar,
    // shade angle, texture projection and lightmap axis where it has none of its own.
    const ShaderInfo& layerShader(const ShaderInfo& parent, const std::string& name);
    // The texture size of a shader, measured on first use when the compile did not measure it.
    TextureSize sizeOf(const ShaderInfo& shader);
    // generatedProjection() with the shader's size, measured only for a q3map_terrain one.
    std::optional<GeneratedProjection> projectionOf(const ShaderInfo& shader);

private:
    const ShaderTable& table_;
    TextureSizes& sizes_;
    const Vfs* vfs_;
    LoadedMap& map_;
    Log& log_;
    std::map<const ShaderInfo*, std::unique_ptr<ShaderInfo>> copies_;  // by the table's shader
};

}  // namespace q3::bspstage
