#include "face_subdivide.h"

#include <cmath>

#include "shader_info.h"

namespace q3::bspstage {
namespace {

void subdivide(Winding w, const DrawSurface& face, float size, const BspEntity& entity, const FaceContext& context,
               const EntitySurfaceParams& params, std::vector<DrawSurface>& out) {
    if (w.empty()) return;
    const DBounds bounds = windingBounds(w);
    for (int axis = 0; axis < 3; ++axis) {
        const int lower = int(std::floor(float(bounds.mins[axis]) / size) * size);
        const int upper = int(std::ceil(float(bounds.maxs[axis]) / size) * size);
        if (float(upper - lower) <= size) continue;
        DPlane plane;
        plane.normal[axis] = -1;
        plane.dist = -(double(lower) + size);
        auto [front, back] = clipWinding(w, plane, 0.1);
        if (front.empty()) {
            w = std::move(back);
        } else if (back.empty()) {
            w = std::move(front);
        } else {
            subdivide(std::move(front), face, size, entity, context, params, out);
            subdivide(std::move(back), face, size, entity, context, params, out);
            return;
        }
    }
    DrawSurface piece = faceSurface(entity, face.brush, face.side, w, params, context, face.fogBackFace);
    piece.fogNum = face.fogNum;
    out.push_back(std::move(piece));
}

}  // namespace

void subdivideFaceSurfaces(std::vector<DrawSurface>& surfaces, const BspEntity& entity, const FaceContext& context,
                           const std::vector<EntitySurfaceParams>& paramsByMapEntity) {
    const size_t count = surfaces.size();
    for (size_t i = 0; i < count; ++i) {
        DrawSurface& ds = surfaces[i];
        if (ds.kind != SurfaceKind::Face || ds.brush < 0) continue;
        const ShaderInfo* si = entity.brushes[size_t(ds.brush)].sides[size_t(ds.side)].shader;
        if (!si || si->isSky() || si->tessSize < 1.0f) continue;
        Winding w;
        for (const bsp::DrawVert& v : ds.verts) w.push_back(DVec3(Vec3::fromArray(v.xyz)));
        const DrawSurface face = ds;
        ds.kind = SurfaceKind::Bad;
        ds.verts.clear();
        ds.indexes.clear();
        std::vector<DrawSurface> pieces;
        subdivide(std::move(w), face, si->tessSize, entity, context, paramsByMapEntity[size_t(face.mapEntityNum)], pieces);
        for (DrawSurface& p : pieces) surfaces.push_back(std::move(p));
    }
}

int tidySurfaces(std::vector<DrawSurface>& surfaces) {
    const size_t before = surfaces.size();
    std::erase_if(surfaces, [](const DrawSurface& ds) {
        return ds.kind != SurfaceKind::Flare && ds.kind != SurfaceKind::Shader &&
               (ds.kind == SurfaceKind::Bad || ds.verts.empty());
    });
    return int(before - surfaces.size());
}

}  // namespace q3::bspstage
