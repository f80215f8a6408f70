// From the shader scripts to what the light stage needs per BSP shader: LightingShader records
// with their light images loaded once through the VFS.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bspfile.h"
#include "lights.h"

namespace q3 {
class Log;
class Vfs;
class ShaderTable;
struct ShaderInfo;
}  // namespace q3

namespace q3::light {

struct LightingShaderSet {
    std::vector<LightingShader> shaders;  // indexed like bsp.shaders
    std::map<std::string, std::unique_ptr<LightImage>> images;  // by VFS image name; owns the images
    int missingImages = 0;
};

// One image read for lighting through the VFS: the image (null when it does not exist) and the
// warning its load gave (empty without one), to be logged where the caller's order says.
struct LightImageRead {
    std::unique_ptr<LightImage> image;
    std::string warning;
};
LightImageRead readLightImage(const Vfs& vfs, const std::string& name);

// The lighting view of one script shader. `image` may be null (no light image found).
LightingShader toLightingShader(const ShaderInfo& info, const LightImage* image);

// One LightingShader per BSP shader. Images are loaded (each once) only for shaders that need them:
// surface lights without q3map_lightRGB, alpha shadows and light filters. `vfs` may be null (no
// images). Names come from the BSP shader lump. Images are decoded on `threads` threads (0: one per
// core); the result and the messages do not depend on their number.
LightingShaderSet resolveLightingShaders(const bsp::Bsp& bsp, const ShaderTable& table, const Vfs* vfs, Log& log,
                                         int threads = 0);

}  // namespace q3::light
