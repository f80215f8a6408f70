#include "flares.h"

#include <cstdlib>
#include <exception>

#include <tbb/parallel_for.h>

#include "bsp_brushes.h"
#include "image.h"
#include "log.h"
#include "map_file.h"
#include "script.h"
#include "shader_info.h"
#include "shader_math.h"
#include "vfs.h"
#include "vfs_image.h"

namespace q3::bspstage {
namespace {

DrawSurface flare(const ShaderInfo& shader, int mapEntityNum, const Vec3& origin, const Vec3& normal, const Vec3& color,
                  int style) {
    DrawSurface ds;
    ds.kind = SurfaceKind::Flare;
    ds.shader = &shader;
    ds.mapEntityNum = mapEntityNum;
    ds.flareOrigin = origin;
    ds.planeNormal = normal;
    ds.flareColor = color;
    ds.lightStyle = style;
    // Flares are never classified: no shadows, no sample size in the .srf.
    ds.castShadows = 0;
    ds.receiveShadows = 0;
    return ds;
}

Vec3 vectorKey(const map::MapEntity& e, const char* key) { return parseVectorKey(e.value(key)).toFloat(); }

}  // namespace

FlareColors FlareColors::load(const std::vector<const ShaderInfo*>& shaders, const Vfs* vfs, Log& log) {
    std::vector<Vec3> colors(shaders.size(), Vec3{1, 1, 1});
    std::vector<std::string> warnings(shaders.size());
    tbb::parallel_for(size_t(0), shaders.size(), [&](size_t i) {
        const ShaderInfo& si = *shaders[i];
        if (si.lightRGB) {
            colors[i] = *si.lightRGB;
            return;
        }
        if (!vfs) return;
        for (const std::string& name : si.lightImageCandidates()) {
            try {
                if (std::optional<LoadedImage> image = loadImage(*vfs, name)) {
                    const ImageAverage average = averageColor(image->image);
                    colors[i] = {average.normalized[0], average.normalized[1], average.normalized[2]};
                    return;
                }
            } catch (const std::exception& e) {
                warnings[i] = e.what();
                return;
            }
        }
    });
    FlareColors out;
    for (size_t i = 0; i < shaders.size(); ++i) {
        if (!warnings[i].empty()) log.warning(warnings[i]);
        out.colors_[shaders[i]] = colors[i];
    }
    return out;
}

Vec3 FlareColors::of(const ShaderInfo& shader) const {
    auto it = colors_.find(&shader);
    return it == colors_.end() ? Vec3{1, 1, 1} : it->second;
}

const ShaderInfo& flareShader(const ShaderTable& shaders, const std::string& name) {
    return shaders.find(name.empty() ? std::string("flareshader") : name);
}

std::vector<DrawSurface> lightFlares(const map::MapFile& file, const ShaderTable& shaders) {
    std::vector<DrawSurface> out;
    for (const map::MapEntity& light : file.entities) {
        if (!equalsNoCase(light.classname(), "light")) continue;
        const std::string* shaderName = light.find("_flareshader");
        if (!shaderName && std::atoi(light.value("_flare").c_str()) == 0) continue;
        const Vec3 origin = vectorKey(light, "origin");
        Vec3 normal{0, 0, -1};
        if (const std::string* target = light.find("target")) {
            for (const map::MapEntity& e : file.entities)
                if (e.value("targetname") == *target && !target->empty()) {
                    normal = vectorKey(e, "origin") - origin;
                    normalizeInPlace(normal);
                    break;
                }
        }
        const int style = std::atoi(light.value("_style", light.value("style")).c_str());
        out.push_back(flare(flareShader(shaders, shaderName ? *shaderName : std::string()), 0, origin, normal,
                            vectorKey(light, "_color"), style >= 0 && style < 256 ? style : 0));
    }
    return out;
}

std::optional<DrawSurface> surfaceFlare(const DrawSurface& ds, const DVec3& entityOrigin, const ShaderTable& shaders,
                                        const FlareColors& colors) {
    const ShaderInfo& si = *ds.shader;
    if (si.flareShader.empty() || ds.verts.empty()) return std::nullopt;
    Vec3 centre{0, 0, 0};
    for (const bsp::DrawVert& v : ds.verts) centre += xyzOf(v);
    centre = centre / float(ds.verts.size()) + entityOrigin.toFloat();
    centre += ds.planeNormal * 2.0f;
    return flare(flareShader(shaders, si.flareShader), ds.mapEntityNum, centre, ds.planeNormal, colors.of(si),
                 si.lightStyle);
}

}  // namespace q3::bspstage
