// ShaderInfo -> LightingShader, with light images loaded once per name (see light_shaders.h).
#include "light_shaders.h"

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cstring>

#include "image.h"
#include "light_text.h"
#include "log.h"
#include "shader_info.h"
#include "vfs.h"
#include "vfs_image.h"

namespace q3::light {
namespace {

bool needsImage(const LightingShader& s) {
    return (s.surfaceLight > 0 && !s.hasLightRGB) || s.alphaShadow || s.lightFilter;
}

// For shaders without a script, the BSP's own flags say what the compiler saw.
void applyBspFlags(LightingShader& s, const bsp::Shader& record) {
    const uint32_t surf = static_cast<uint32_t>(record.surfaceFlags);
    const uint32_t cont = static_cast<uint32_t>(record.contentFlags);
    s.sky = s.sky || (surf & q3::surfaceflags::Sky);
    s.nodraw = s.nodraw || (surf & q3::surfaceflags::NoDraw);
    s.alphaShadow = s.alphaShadow || (surf & q3::surfaceflags::AlphaShadow);
    s.lightFilter = s.lightFilter || (surf & q3::surfaceflags::LightFilter);
    s.vertexLit = s.vertexLit || (surf & q3::surfaceflags::VertexLit);
    s.translucent = s.translucent || (cont & q3::contents::Translucent);
    s.fog = s.fog || (cont & q3::contents::Fog);
}

// What a BSP shader is before its light image is known (which images it needs follows from it).
LightingShader shaderWithoutImage(const ShaderInfo& info, const bsp::Shader& record) {
    LightingShader probe = toLightingShader(info, nullptr);
    if (!info.explicitScript) applyBspFlags(probe, record);
    return probe;
}

// The image of that name from the cache, taking it from `ahead` or loading it on first use; null
// when it does not exist.
const LightImage* cachedImage(LightingShaderSet& set, std::map<std::string, LightImageRead>& ahead, const Vfs& vfs,
                              const std::string& name, Log& log) {
    auto it = set.images.find(name);
    if (it != set.images.end()) return it->second.get();
    const auto early = ahead.find(name);
    LightImageRead loaded = early != ahead.end() ? std::move(early->second) : readLightImage(vfs, name);
    if (!loaded.warning.empty()) log.warning(loaded.warning);
    const LightImage* image = loaded.image.get();
    set.images.emplace(name, std::move(loaded.image));
    return image;
}

constexpr const char* kSkyBoxSuffixes[6] = {"_lf", "_rt", "_ft", "_bk", "_up", "_dn"};

bool wantsSkyColors(const LightingShader& s) {
    return std::any_of(s.skyLights.begin(), s.skyLights.end(), [](const SkyLightDirective& d) { return d.sampleColor; });
}

// The images the shaders will first ask for (each shader's first light image candidate, the sky
// boxes whose colours sky lights sample), decoded in parallel: a map whose area lights take their
// colour from their textures decodes dozens of them.
std::map<std::string, LightImageRead> readImagesAhead(const bsp::Bsp& bsp, const ShaderTable& table,
                                                      const Vfs& vfs, int threads) {
    std::vector<std::string> names;
    for (const bsp::Shader& record : bsp.shaders) {
        const ShaderInfo& info = table.find(std::string(record.name, strnlen(record.name, sizeof(record.name))));
        const LightingShader probe = shaderWithoutImage(info, record);
        if (needsImage(probe)) {
            const std::vector<std::string> candidates = info.lightImageCandidates();
            if (!candidates.empty()) names.push_back(candidates.front());
        }
        if (wantsSkyColors(probe) && !info.skyParmsEnv.empty())
            for (const char* suffix : kSkyBoxSuffixes) names.push_back(info.skyParmsEnv + suffix);
    }
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    std::vector<LightImageRead> read(names.size());
    tbb::task_arena(threads > 0 ? threads : tbb::task_arena::automatic).execute([&] {
        tbb::parallel_for(size_t(0), names.size(), [&](size_t i) { read[i] = readLightImage(vfs, names[i]); });
    });
    std::map<std::string, LightImageRead> out;
    for (size_t i = 0; i < names.size(); ++i) out.emplace(names[i], std::move(read[i]));
    return out;
}

}  // namespace

LightImageRead readLightImage(const Vfs& vfs, const std::string& name) {
    LightImageRead out;
    try {
        if (std::optional<LoadedImage> li = loadImage(vfs, name)) {
            out.image = std::make_unique<LightImage>();
            out.image->width = li->image.width;
            out.image->height = li->image.height;
            out.image->rgba = std::move(li->image.rgba);
        }
    } catch (const std::exception& e) {
        out.warning = e.what();
    }
    return out;
}

LightingShader toLightingShader(const ShaderInfo& info, const LightImage* image) {
    LightingShader s;
    s.name = info.name;
    s.sky = info.isSky();
    s.translucent = info.isTranslucent();
    s.nodraw = info.isNoDraw();
    s.alphaShadow = info.isAlphaShadow();
    s.lightFilter = info.isLightFilter();
    s.twoSided = info.twoSided;
    s.fog = info.isFog();
    s.vertexLit = info.isVertexLit();
    s.autosprite = info.autosprite;
    for (const ShaderSun& sun : info.suns) {
        SunDirective d;
        d.color = sun.color;
        d.intensity = sun.intensity;
        d.direction = sun.direction;
        d.devianceDeg = sun.devianceDegrees;
        d.samples = sun.samples;
        d.style = sun.style;
        d.filterRadius = sun.filterRadius;
        s.suns.push_back(d);
    }
    for (const ShaderSkyLight& sky : info.skyLights) {
        SkyLightDirective d;
        d.value = sky.value;
        d.iterations = sky.iterations;
        d.horizonMin = static_cast<float>(sky.horizonMin);
        d.horizonMax = static_cast<float>(sky.horizonMax);
        d.sampleColor = sky.sampleColor;
        s.skyLights.push_back(d);
    }
    s.surfaceLight = info.surfaceLight;
    s.hasLightRGB = info.lightRGB.has_value();
    if (info.lightRGB) {
        s.color = *info.lightRGB;
    } else if (image && image->width > 0) {
        Vec3 avg = image->averageColor();
        float m = maxComponent(avg);
        s.color = m > 0 ? avg / m : Vec3{1, 1, 1};
    }
    s.lightSubdivide = static_cast<float>(info.lightSubdivide);
    s.lightStyle = info.lightStyle;
    s.backsplashFraction = info.backsplashFraction;
    s.backsplashDistance = info.backsplashDistance;
    s.backsplashSet = info.backsplashSet;
    s.lightFilterRadius = info.lightFilterRadius;
    s.bounceScale = info.bounceScale;
    s.lightImage = image;
    s.lightmapSampleSize = info.lightmapSampleSize;
    s.lightmapAxis = info.lightmapAxis;
    s.lightmapSampleOffset = info.lightmapSampleOffset;
    s.lightmapFilterRadius = info.lightmapFilterRadius;
    s.lightmapBrightness = info.lightmapBrightness;
    s.vertexScale = info.vertexScale;
    s.noVertexLight = info.noVertexLight;
    s.forceSunlight = info.forceSunlight;
    return s;
}

LightingShaderSet resolveLightingShaders(const bsp::Bsp& bsp, const ShaderTable& table, const Vfs* vfs, Log& log,
                                         int threads) {
    LightingShaderSet set;
    set.shaders.reserve(bsp.shaders.size());
    std::map<std::string, LightImageRead> ahead;
    if (vfs) ahead = readImagesAhead(bsp, table, *vfs, threads);
    for (const bsp::Shader& record : bsp.shaders) {
        const std::string name(record.name, strnlen(record.name, sizeof(record.name)));
        const ShaderInfo& info = table.find(name);
        const LightingShader probe = shaderWithoutImage(info, record);

        const LightImage* image = nullptr;
        if (vfs && needsImage(probe)) {
            for (const std::string& candidate : info.lightImageCandidates()) {
                image = cachedImage(set, ahead, *vfs, candidate, log);
                if (image) break;
            }
            if (!image) {
                ++set.missingImages;
                log.debug(strCat("shader ", name, ": no light image found"));
            }
        }
        LightingShader resolved = toLightingShader(info, image);
        if (!info.explicitScript) applyBspFlags(resolved, record);
        if (vfs && wantsSkyColors(resolved) && !info.skyParmsEnv.empty()) {
            for (size_t k = 0; k < 6; ++k) {
                resolved.skyBox[k] = cachedImage(set, ahead, *vfs, info.skyParmsEnv + kSkyBoxSuffixes[k], log);
                if (!resolved.skyBox[k])
                    log.warning(strCat("shader ", name, ": sky image ", info.skyParmsEnv, kSkyBoxSuffixes[k],
                                       " not found, sky light keeps the shader colour"));
            }
        }
        set.shaders.push_back(std::move(resolved));
    }
    return set;
}

}  // namespace q3::light
