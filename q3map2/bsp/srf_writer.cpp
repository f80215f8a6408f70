#include "srf_writer.h"

#include <cstdio>

namespace q3::bspstage {
namespace {

std::string formatted(const char* pattern, double a, double b = 0, double c = 0) {
    char text[160];
    std::snprintf(text, sizeof text, pattern, a, b, c);
    return text;
}

}  // namespace

std::string surfaceExtraText(const std::vector<const DrawSurface*>& surfaces, int defaultSampleSize,
                             const LoadedMap& map, std::span<const EntitySurfaceParams> entityParams) {
    const int defaultCast = 1, defaultReceive = 1;
    const Vec3 defaultAmbient = entityParams.empty() ? Vec3{0, 0, 0} : entityParams[0].ambientColor;
    auto ambientOf = [&](const DrawSurface& ds) {
        const int entity = ds.modelEntity >= 0 ? ds.modelEntity : ds.mapEntityNum;
        return entity >= 0 && size_t(entity) < entityParams.size() ? entityParams[size_t(entity)].ambientColor
                                                                   : Vec3{0, 0, 0};
    };
    std::string out = "default\n{\n";
    out += "\tcastShadows " + std::to_string(defaultCast) + "\n";
    out += "\treceiveShadows " + std::to_string(defaultReceive) + "\n";
    out += "\tsampleSize " + std::to_string(defaultSampleSize) + "\n";
    out += formatted("\tambientColor ( %f %f %f )\n", defaultAmbient.x, defaultAmbient.y, defaultAmbient.z);
    out += "\tlongestCurve 0.000000\n";
    out += "}\n\n";
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const DrawSurface& ds = *surfaces[i];
        out += std::to_string(i) + " // " + std::string(surfaceKindName(ds.kind)) + " V: " +
               std::to_string(ds.verts.size()) + " I: " + std::to_string(ds.indexes.size()) + " " +
               (ds.planar ? "planar" : "") + "\n{\n";
        out += "\tshader " + map.shaderName(*ds.shader) + "\n";
        if (ds.parentSurface >= 0) out += "\tparent " + std::to_string(ds.parentSurface) + "\n";
        if (ds.mapEntityNum != 0) out += "\tentity " + std::to_string(ds.mapEntityNum) + "\n";
        if (ds.castShadows != defaultCast) out += "\tcastShadows " + std::to_string(ds.castShadows) + "\n";
        if (ds.receiveShadows != defaultReceive) out += "\treceiveShadows " + std::to_string(ds.receiveShadows) + "\n";
        if (ds.sampleSize != defaultSampleSize) out += "\tsampleSize " + std::to_string(ds.sampleSize) + "\n";
        // Zero means "the default's", as in q3map2.
        if (const Vec3 ambient = ambientOf(ds); ambient != Vec3{0, 0, 0} && ambient != defaultAmbient)
            out += formatted("\tambientColor ( %f %f %f )\n", ambient.x, ambient.y, ambient.z);
        if (ds.longestCurve != 0) out += formatted("\tlongestCurve %f\n", ds.longestCurve);
        if (ds.lightmapAxis != Vec3{0, 0, 0})
            out += formatted("\tlightmapAxis ( %f %f %f )\n", ds.lightmapAxis.x, ds.lightmapAxis.y, ds.lightmapAxis.z);
        out += "}\n\n";
    }
    return out;
}

}  // namespace q3::bspstage
