#include "texture_sizes.h"

#include <exception>

#include "log.h"
#include "shader_info.h"
#include "vfs.h"
#include "vfs_image.h"

namespace q3::bspstage {
namespace {

TextureSize sizeOf(const ShaderInfo& shader, const Vfs& vfs, Log& log) {
    if (shader.textureWidth > 0 && shader.textureHeight > 0) return {shader.textureWidth, shader.textureHeight};
    TextureSize size = kDefaultTextureSize;
    bool found = shader.isNoDraw();  // nodraw faces are never drawn: q3map2 gives them the default
    if (!found) {
        for (const std::string& name : shader.textureImageCandidates()) {
            try {
                if (std::optional<LoadedImage> image = loadImage(vfs, name)) {
                    size = {image->image.width, image->image.height};
                    found = true;
                    break;
                }
            } catch (const std::exception& e) {
                log.warning(e.what());
            }
        }
        if (!found) log.warning("Couldn't find image for shader " + shader.name);
    }
    return size;
}

}  // namespace

TextureSizes TextureSizes::load(const std::vector<const ShaderInfo*>& shaders, const Vfs& vfs, Log& log) {
    TextureSizes out;
    for (const ShaderInfo* shader : shaders)
        if (shader && !out.sizes_.count(shader)) out.sizes_[shader] = sizeOf(*shader, vfs, log);
    return out;
}

TextureSize TextureSizes::of(const ShaderInfo& shader) const {
    auto it = sizes_.find(&shader);
    return it == sizes_.end() ? kDefaultTextureSize : it->second;
}

}  // namespace q3::bspstage
