#include <algorithm>
#include <cmath>

#include "decals.h"
#include "meta/patch_meta.h"
#include "patch.h"
#include "plane_set.h"
#include "shader_info.h"
#include "winding.h"

namespace q3::bspstage {
namespace {

// The projector moved into a model's frame (q3map2 TransformDecalProjector with no rotation).
DecalProjector inModelFrame(const DecalProjector& in, const Vec3& origin) {
    DecalProjector out = in;
    out.mins = in.mins - origin;
    out.maxs = in.maxs - origin;
    out.center = in.center - origin;
    for (int i = 0; i < in.numPlanes; ++i) out.planes[i].dist = in.planes[i].dist - dot(in.planes[i].normal, origin);
    for (int i = 0; i < 2; ++i) {
        const Vec3 row{in.texMat[i][0], in.texMat[i][1], in.texMat[i][2]};
        out.texMat[i][3] = dot(row, origin) + in.texMat[i][3];
    }
    return out;
}

// Whether the sphere's centre lies within the surface's bounds grown by the radius.
bool reaches(const DrawSurface& ds, const DecalProjector& dp) {
    Bounds b;
    for (const bsp::DrawVert& v : ds.verts) b.add(xyzOf(v));
    for (int k = 0; k < 3; ++k)
        if (dp.center[k] < b.mins[k] - dp.radius || dp.center[k] > b.maxs[k] + dp.radius) return false;
    return true;
}

bool facesAway(const DecalProjector& dp, const Vec3& normal) { return dot(dp.planes[0].normal, normal) < -0.0001f; }

uint8_t alphaByte(float alpha) {
    if (std::isnan(alpha)) return 0;
    return uint8_t(std::clamp(alpha, 0.0f, 255.0f));
}

struct Projection {
    const DecalProjector& dp;
    const DrawSurface& target;
    std::vector<DrawSurface>& out;
};

// Clips the polygon to the prism and, when something is left, adds it as a Decal surface.
void projectOntoPolygon(Projection& p, const std::vector<Vec3>& points) {
    if (points.size() < 3) return;
    FPlane plane;
    if (!floatPlaneFromPoints(plane, points[0], points[1], points[2])) return;
    if (facesAway(p.dp, plane.normal)) return;
    Winding w;
    for (const Vec3& v : points) w.push_back(DVec3(v));
    for (int i = 0; i < p.dp.numPlanes; ++i) {
        const FPlane& cut = p.dp.planes[i];
        w = clipWindingStrict(w, DPlane{DVec3(cut.normal), double(cut.dist)}, 0.0625).second;
        if (w.empty()) return;
    }
    if (w.size() < 3) return;

    DrawSurface ds;
    ds.kind = SurfaceKind::Decal;
    ds.shader = p.dp.shader;
    ds.mapEntityNum = p.target.mapEntityNum;
    ds.castShadows = p.target.castShadows;
    ds.receiveShadows = p.target.receiveShadows;
    ds.fogNum = p.target.fogNum;
    ds.lightmapScale = p.target.lightmapScale;
    ds.shadeAngle = p.target.shadeAngle;
    for (const DVec3& point : w) {
        const Vec3 xyz = point.toFloat();
        bsp::DrawVert v{};
        xyz.toArray(v.xyz);
        plane.normal.toArray(v.normal);
        for (int i = 0; i < 2; ++i)
            v.st[i] = dot(xyz, Vec3{p.dp.texMat[i][0], p.dp.texMat[i][1], p.dp.texMat[i][2]}) + p.dp.texMat[i][3];
        // Opaque at the patch, fading out towards the far end of the prism.
        const float front = p.dp.planes[0].distanceTo(xyz), back = p.dp.planes[1].distanceTo(xyz);
        v.color[0] = v.color[1] = v.color[2] = 255;
        v.color[3] = alphaByte(255.0f * back / (front + back));
        ds.verts.push_back(v);
    }
    p.out.push_back(std::move(ds));
}

void projectOntoTriangles(Projection& p, const std::vector<bsp::DrawVert>& verts, const std::vector<int>& indexes) {
    for (size_t i = 0; i + 2 < indexes.size(); i += 3)
        projectOntoPolygon(p, {xyzOf(verts[size_t(indexes[i])]), xyzOf(verts[size_t(indexes[i + 1])]),
                               xyzOf(verts[size_t(indexes[i + 2])])});
}

}  // namespace

int makeEntityDecals(const DecalInputs& in, std::vector<DrawSurface>& surfaces) {
    std::vector<DrawSurface> decals;
    const Vec3 origin = in.entityOrigin.toFloat();
    for (const DecalProjector& world : in.projectors) {
        const DecalProjector dp = inModelFrame(world, origin);
        for (const DrawSurface& ds : surfaces) {
            if (ds.verts.empty()) continue;
            if (ds.shader->autosprite || (ds.shader->compileFlags & compileflags::NoMarks)) continue;
            if (!reaches(ds, dp)) continue;
            if (ds.planar && ds.planeNum >= 0 && facesAway(dp, in.planes[ds.planeNum].normal().toFloat())) continue;
            Projection p{dp, ds, decals};
            switch (ds.kind) {
                case SurfaceKind::Face: {
                    if (ds.side < 0 || ds.fogBackFace) break;  // only faces drawn from a brush side
                    std::vector<Vec3> points;
                    for (const bsp::DrawVert& v : ds.verts) points.push_back(xyzOf(v));
                    projectOntoPolygon(p, points);
                    break;
                }
                case SurfaceKind::Patch: {
                    const patch::PatchMesh mesh = patch::tessellateForLighting(meta::surfaceControlGrid(ds),
                                                                               ds.longestCurve, in.patchSubdivisions);
                    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
                        projectOntoPolygon(p, {mesh.verts[mesh.indices[i]].xyz, mesh.verts[mesh.indices[i + 1]].xyz,
                                               mesh.verts[mesh.indices[i + 2]].xyz});
                    break;
                }
                case SurfaceKind::Triangles:
                    // Model triangles without a shader script take no marks.
                    if (!ds.shader->explicitScript) break;
                    projectOntoTriangles(p, ds.verts, ds.indexes);
                    break;
                case SurfaceKind::ForcedMeta:
                case SurfaceKind::Meta:
                    projectOntoTriangles(p, ds.verts, ds.indexes);
                    break;
                default:
                    break;
            }
        }
    }
    const int made = int(decals.size());
    for (DrawSurface& ds : decals) surfaces.push_back(std::move(ds));
    return made;
}

}  // namespace q3::bspstage
