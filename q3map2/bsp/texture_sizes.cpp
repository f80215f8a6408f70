#include "texture_sizes.h"

#include <algorithm>
#include <exception>
#include <string>

#include <tbb/parallel_for.h>

#include "log.h"
#include "shader_info.h"
#include "vfs.h"
#include "vfs_image.h"

namespace q3::bspstage {
namespace {

// The size of one shader's image and the warning to give (empty when none); `log` is not touched,
// so that shaders can be measured in parallel and their warnings printed in order afterwards.
struct Measured {
    TextureSize size;
    std::vector<std::string> warnings;
};

Measured measure(const ShaderInfo& shader, const Vfs& vfs) {
    Measured out;
    if (shader.textureWidth > 0 && shader.textureHeight > 0) {
        out.size = {shader.textureWidth, shader.textureHeight};
        return out;
    }
    if (shader.isNoDraw()) return out;  // nodraw faces are never drawn: q3map2 gives them the default
    for (const std::string& name : shader.textureImageCandidates()) {
        try {
            if (std::optional<ImageDimensions> image = loadImageDimensions(vfs, name)) {
                out.size = {image->width, image->height};
                return out;
            }
        } catch (const std::exception& e) {
            out.warnings.push_back(e.what());
        }
    }
    out.warnings.push_back("Couldn't find image for shader " + shader.name);
    return out;
}

}  // namespace

TextureSizes TextureSizes::load(const std::vector<const ShaderInfo*>& shaders, const Vfs& vfs, Log& log) {
    std::vector<const ShaderInfo*> unique;
    for (const ShaderInfo* shader : shaders)
        if (shader && std::find(unique.begin(), unique.end(), shader) == unique.end()) unique.push_back(shader);
    // Images are measured in parallel into one slot per shader; warnings follow the shader order.
    std::vector<Measured> measured(unique.size());
    tbb::parallel_for(size_t(0), unique.size(), [&](size_t i) { measured[i] = measure(*unique[i], vfs); });
    TextureSizes out;
    for (size_t i = 0; i < unique.size(); ++i) {
        for (const std::string& w : measured[i].warnings) log.warning(w);
        out.sizes_[unique[i]] = measured[i].size;
    }
    return out;
}

TextureSize TextureSizes::of(const ShaderInfo& shader) const {
    auto it = sizes_.find(&shader);
    return it == sizes_.end() ? kDefaultTextureSize : it->second;
}

}  // namespace q3::bspstage
