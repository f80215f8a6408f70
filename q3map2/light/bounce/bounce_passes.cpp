// Emitters of the -bounce passes (bounce_passes.h).
#include "bounce_passes.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <span>

#include "bounce_lights.h"
#include "file_io.h"
#include "light_context.h"
#include "light_text.h"
#include "patch.h"
#include "surface_lighting.h"

namespace q3::light {
namespace {

// Vertices and triangles of a lit surface in world space, with texture and lightmap coordinates
// (`coords`: its draw vertices' coordinates in the lightmap it shares).
void emitterGeometry(const LightContext& ctx, int surfaceNum, std::span<const std::array<float, 2>> coords,
                     BounceSurface& out) {
    const bsp::Surface& s = ctx.bsp.surfaces[size_t(surfaceNum)];
    const Vec3 offset = ctx.surfaceOffsets[size_t(surfaceNum)];
    auto lightmapCoord = [&](int v) { return size_t(v) < coords.size() ? coords[size_t(v)] : std::array<float, 2>{}; };
    if (s.surfaceType == bsp::MST_PATCH) {
        // The lighting tessellation carries texture and lightmap coordinates through the curve.
        patch::ControlGrid grid = patchControlGrid(ctx.bsp, s, offset);
        for (size_t v = 0; v < grid.points.size(); ++v) {
            grid.points[v].lightmap[0] = lightmapCoord(int(v))[0];
            grid.points[v].lightmap[1] = lightmapCoord(int(v))[1];
        }
        if (!patch::isValidGrid(grid)) return;
        const patch::PatchMesh mesh = patch::tessellateForLighting(grid);
        for (const patch::PatchVertex& v : mesh.verts)
            out.verts.push_back({v.xyz, v.normal, {v.st[0], v.st[1]}, {v.lightmap[0], v.lightmap[1]}});
        out.triangles = mesh.indices;
        return;
    }
    for (int v = 0; v < s.numVerts; ++v) {
        const bsp::DrawVert& dv = ctx.bsp.drawVerts[size_t(s.firstVert + v)];
        out.verts.push_back({Vec3::fromArray(dv.xyz) + offset, Vec3::fromArray(dv.normal), {dv.st[0], dv.st[1]},
                             lightmapCoord(v)});
    }
    for (int i = 0; i + 2 < s.numIndexes; i += 3) {
        const int32_t a = ctx.bsp.drawIndexes[size_t(s.firstIndex + i)];
        const int32_t b = ctx.bsp.drawIndexes[size_t(s.firstIndex + i + 1)];
        const int32_t c = ctx.bsp.drawIndexes[size_t(s.firstIndex + i + 2)];
        if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= s.numVerts) continue;
        out.triangles.insert(out.triangles.end(), {uint32_t(a), uint32_t(b), uint32_t(c)});
    }
}

// The form factor of an emitter counts for receivers in front of it when its winding runs clockwise
// seen from the front (the order of BSP triangles); emitters cut from surfaces whose triangles run
// the other way are turned round, so that they light the side their normal faces.
void orientWinding(Light& light) {
    Vec3 area;
    for (size_t i = 0; i < light.winding.size(); ++i)
        area += cross(light.winding[i], light.winding[(i + 1) % light.winding.size()]);
    if (dot(area, light.normal) > 0) std::reverse(light.winding.begin(), light.winding.end());
}

}  // namespace

BouncePasses::BouncePasses(const LightContext& ctx, const std::vector<ShaderAlbedo>& albedo, Log& log)
    : ctx_(ctx), log_(log), albedo_(albedo) {}

std::vector<Light> BouncePasses::emitters(const std::vector<SurfaceLight>& previous, int bounce, Vec3 ambient) {
    std::vector<BounceSurface> surfaces;
    for (const SurfaceLight& lit : previous) {
        if (!lit.ok) continue;
        // Every surface of a shared lightmap emits from its own triangles (q3map2 walks surfaces).
        for (size_t m = 0; m < lit.layout.surfaces.size() && m < lit.layout.surfaceCoords.size(); ++m) {
            const int surfaceNum = lit.layout.surfaces[m];
            const bsp::Surface& s = ctx_.bsp.surfaces[size_t(surfaceNum)];
            const size_t shaderNum = size_t(s.shaderNum);
            BounceSurface geometry;
            geometry.surfaceNum = surfaceNum;
            geometry.shader = &ctx_.shaders.shaders[shaderNum];
            geometry.shaderBounceScale = ctx_.shaders.shaders[shaderNum].bounceScale;
            if (shaderNum < albedo_.size()) {
                geometry.image = albedo_[shaderNum].image;
                geometry.averageColor = albedo_[shaderNum].average;
            }
            geometry.width = lit.width;
            geometry.height = lit.height;
            geometry.lit = lit.used;
            emitterGeometry(ctx_, surfaceNum, lit.layout.surfaceCoords[m], geometry);
            for (const LightmapLayer& layer : lit.layers) {
                BounceSurface styled = geometry;
                styled.style = layer.style;
                styled.luxels = layer.color;
                if (layer.style == 0)
                    for (Vec3& c : styled.luxels) c = vmax(c - ambient, Vec3{});
                surfaces.push_back(std::move(styled));
            }
        }
    }
    BounceSettings settings;
    settings.bounceScale = ctx_.options.bounceScale;
    settings.colorRatio = ctx_.options.bounceColorRatio;
    settings.falloffTolerance = ctx_.scales.falloffTolerance;
    settings.fast = ctx_.options.fastBounce || ctx_.options.fast || ctx_.options.faster;
    settings.noStyles = ctx_.options.noStyles;
    std::vector<Light> lights = createBounceLights(surfaces, settings);
    for (Light& light : lights) orientWinding(light);
    const int inSolid = assignLightClusters(ctx_, lights);
    log_.info(strCat("bounce ", bounce, ": ", lights.size(), " diffuse lights from ", surfaces.size(),
                     " surfaces", inSolid > 0 ? strCat(" (", inSolid, " in solid removed)") : std::string()));
    if (ctx_.options.dump) {
        char suffix[32];
        std::snprintf(suffix, sizeof(suffix), "_bounce_%03d.map", bounce - 1);
        std::filesystem::path path = ctx_.bspPath;
        path.replace_extension();
        path += suffix;
        writeFileAtomic(path, bounceLightsAsMap(lights));
        log_.info(strCat("Writing ", path.string()));
    }
    return lights;
}

}  // namespace q3::light
