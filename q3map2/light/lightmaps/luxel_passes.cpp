#include "luxel_passes.h"

#include <oneapi/tbb/task_arena.h>

#include "light_context.h"
#include "light_text.h"
#include "shader_info.h"

namespace q3::light {

std::unique_ptr<LuxelPasses> prepareLuxelPasses(const LightContext& ctx, Log& log) {
    auto passes = std::make_unique<LuxelPasses>();
    const LightOptions& o = ctx.options;
    passes->dirty = o.dirty;
    passes->dirt = dirtSettingsFromOptions(o);
    if (!ctx.entities.empty())
        passes->globalFlood = globalFloodlight(o.floodlight, o.lowQuality, ctx.entities.front(), ctx.bspPath.string());
    else if (o.floodlight)
        passes->globalFlood = globalFloodlight(true, o.lowQuality, bsp::Entity{}, ctx.bspPath.string());

    const size_t shaderCount = ctx.bsp.shaders.size();
    passes->noDirty.assign(shaderCount, 0);
    passes->shaderFlood.assign(shaderCount, std::nullopt);
    bool anyShaderFlood = false;
    if (ctx.shaderTable) {
        for (size_t i = 0; i < shaderCount; ++i) {
            const ShaderInfo& info = ctx.shaderTable->find(ctx.bsp.shaders[i].name);
            passes->noDirty[i] = info.noDirty ? 1 : 0;
            passes->shaderFlood[i] = shaderFloodlight(info.floodLight);
            anyShaderFlood = anyShaderFlood || passes->shaderFlood[i].has_value();
        }
    }
    if (!passes->dirty && !passes->globalFlood && !anyShaderFlood) return nullptr;
    if (passes->globalFlood)
        log.info(strCat("floodlight: intensity ", passes->globalFlood->intensity, ", distance ",
                        passes->globalFlood->distance));
    if (passes->dirty)
        log.info(strCat("dirt mapping: mode ", passes->dirt.mode, ", depth ", passes->dirt.depth, ", scale ",
                        passes->dirt.scale, ", gain ", passes->dirt.gain));
    TraceSceneOptions sceneOptions;
    sceneOptions.patchShadows = o.patchShadows;
    if (ctx.tree && ctx.tree->hasNodes()) passes->tree = ctx.tree.get();
    const SolidBackedTest backed = passes->dirty && passes->tree ? dirtSolidBacked(*passes->tree) : SolidBackedTest{};
    tbb::task_arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic).execute([&] {
        passes->scene = std::make_unique<HitScene>(ctx.surfaces, sceneOptions, backed);
    });
    return passes;
}

void applyLuxelPasses(const LuxelPasses& passes, int shaderNum, LuxelImage& image,
                      const std::vector<std::optional<SamplePoint>>& points) {
    const bool known = shaderNum >= 0 && static_cast<size_t>(shaderNum) < passes.noDirty.size();
    if (passes.globalFlood) addFloodlight(image, floodlightForLightmap(points, *passes.scene, *passes.globalFlood));
    if (known && passes.shaderFlood[static_cast<size_t>(shaderNum)])
        addFloodlight(image,
                      floodlightForLightmap(points, *passes.scene, *passes.shaderFlood[static_cast<size_t>(shaderNum)]));
    if (passes.dirty) {
        const bool noDirty = known && passes.noDirty[static_cast<size_t>(shaderNum)];
        // -dirtdebug shows the factor itself, so every luxel needs it.
        const std::vector<uint8_t> wanted = passes.dirt.debug ? std::vector<uint8_t>{} : dirtWantedLuxels(image);
        applyDirt(image, dirtForLightmap(points, image.width, image.height, *passes.scene, passes.dirt, noDirty,
                                         passes.tree, wanted),
                  passes.dirt.debug);
    }
}

}  // namespace q3::light
