// The image size that scales a shader's brush face texture coordinates (q3map2 LoadShaderImages):
// q3map_textureSize if given (then no image is looked for), else the first of editor image, shader
// name, implicit image and light image that loads; nodraw shaders and shaders without any image
// use q3map2's 64x64 default.
#pragma once

#include <map>
#include <vector>

namespace q3 {
class Log;
class Vfs;
struct ShaderInfo;
}  // namespace q3

namespace q3::bspstage {

struct TextureSize {
    int width = 64;
    int height = 64;
};

inline constexpr TextureSize kDefaultTextureSize{64, 64};

class TextureSizes {
public:
    // Sizes for `shaders` (each looked up once); "Couldn't find image for shader" warnings go to
    // `log`, as q3map2 prints them.
    static TextureSizes load(const std::vector<const ShaderInfo*>& shaders, const Vfs& vfs, Log& log);

    // The size of a shader given to load(); the default size for any other.
    TextureSize of(const ShaderInfo& shader) const;
    void set(const ShaderInfo& shader, TextureSize size) { sizes_[&shader] = size; }
    bool contains(const ShaderInfo& shader) const { return sizes_.count(&shader) != 0; }

private:
    std::map<const ShaderInfo*, TextureSize> sizes_;
};

}  // namespace q3::bspstage
