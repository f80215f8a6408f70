#include "fog_hull.h"

namespace q3::bspstage {

std::optional<DrawSurface> fogHullSurface(const std::string& value, const DBounds& worldBounds,
                                          const ShaderTable& shaders) {
    if (value.empty()) return std::nullopt;
    const Vec3 lo = worldBounds.mins.toFloat() - Vec3{128, 128, 128};
    const Vec3 hi = worldBounds.maxs.toFloat() + Vec3{128, 128, 128};
    DrawSurface ds;
    ds.kind = SurfaceKind::Foghull;
    ds.shader = &shaders.find("textures/" + value);
    // q3map2 leaves everything but the positions zero: no normal, colour or lighting keys.
    ds.castShadows = 0;
    ds.receiveShadows = 0;
    const Vec3 corners[8] = {{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z},
                             {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}};
    for (const Vec3& c : corners) {
        bsp::DrawVert v{};
        c.toArray(v.xyz);
        ds.verts.push_back(v);
    }
    // Bottom, top, then the four sides, facing in.
    ds.indexes = {0, 1, 2, 0, 2, 3, 4, 7, 5, 5, 7, 6, 1, 5, 6, 1, 6, 2,
                  0, 4, 5, 0, 5, 1, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
    return ds;
}

}  // namespace q3::bspstage
