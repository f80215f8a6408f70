#include "terrain_shaders.h"

#include "bsp_brushes.h"
#include "shader_info.h"

namespace q3::bspstage {

std::optional<GeneratedProjection> generatedProjection(const ShaderInfo& shader, TextureSize size) {
    if (shader.tcGen) return GeneratedProjection{shader.tcGenVectors[0], shader.tcGenVectors[1]};
    if (!shader.legacyTerrain) return std::nullopt;
    return GeneratedProjection{{1.0f / (float(size.width) * 0.5f), 0, 0}, {0, 1.0f / (float(size.height) * 0.5f), 0}};
}

TerrainShaders::TerrainShaders(const ShaderTable& table, TextureSizes& sizes, const Vfs* vfs, LoadedMap& map, Log& log)
    : table_(table), sizes_(sizes), vfs_(vfs), map_(map), log_(log) {}

TextureSize TerrainShaders::sizeOf(const ShaderInfo& shader) {
    if (!sizes_.contains(shader) && vfs_) sizes_.set(shader, TextureSizes::load({&shader}, *vfs_, log_).of(shader));
    return sizes_.of(shader);
}

std::optional<GeneratedProjection> TerrainShaders::projectionOf(const ShaderInfo& shader) {
    const bool measured = shader.legacyTerrain && !shader.tcGen;
    return generatedProjection(shader, measured ? sizeOf(shader) : kDefaultTextureSize);
}

const ShaderInfo& TerrainShaders::layerShader(const ShaderInfo& parent, const std::string& name) {
    const ShaderInfo& found = table_.find(name);
    std::unique_ptr<ShaderInfo>& copy = copies_[&found];
    if (!copy) {
        copy = std::make_unique<ShaderInfo>(found);
        const TextureSize size = sizeOf(found);
        sizes_.set(*copy, size);
        // The layer shader is finished before it adopts anything: its own terrain projection first.
        if (const std::optional<GeneratedProjection> own = generatedProjection(*copy, size)) {
            copy->tcGen = true;
            copy->tcGenVectors[0] = own->s;
            copy->tcGenVectors[1] = own->t;
        }
        if (!found.explicitScript) map_.implicitShaderNames.try_emplace(copy.get(), name);
    }
    ShaderInfo& layer = *copy;
    if (parent.globalTexture) layer.globalTexture = true;
    if (parent.forceMeta) layer.forceMeta = true;
    if (parent.nonplanar) layer.nonplanar = true;
    if (layer.shadeAngleDegrees == 0) layer.shadeAngleDegrees = parent.shadeAngleDegrees;
    if (!layer.tcGen)
        if (const std::optional<GeneratedProjection> p = projectionOf(parent)) {
            layer.tcGen = true;
            layer.tcGenVectors[0] = p->s;
            layer.tcGenVectors[1] = p->t;
        }
    if (parent.lightmapAxis >= 0 && layer.lightmapAxis < 0) layer.lightmapAxis = parent.lightmapAxis;
    return layer;
}

}  // namespace q3::bspstage
