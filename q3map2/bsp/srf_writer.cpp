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
                             const LoadedMap& map) {
    const int defaultCast = 1, defaultReceive = 1;
    std::string out = "default\n{\n";
    out += "\tcastShadows " + std::to_string(defaultCast) + "\n";
    out += "\treceiveShadows " + std::to_string(defaultReceive) + "\n";
    out += "\tsampleSize " + std::to_string(defaultSampleSize) + "\n";
    out += "\tambientColor ( 0.000000 0.000000 0.000000 )\n";
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
        if (ds.longestCurve != 0) out += formatted("\tlongestCurve %f\n", ds.longestCurve);
        if (ds.lightmapAxis != Vec3{0, 0, 0})
            out += formatted("\tlightmapAxis ( %f %f %f )\n", ds.lightmapAxis.x, ds.lightmapAxis.y, ds.lightmapAxis.z);
        out += "}\n\n";
    }
    return out;
}

}  // namespace q3::bspstage
