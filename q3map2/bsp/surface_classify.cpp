#include "surface_classify.h"

#include <algorithm>
#include <cmath>

#include "shader_info.h"

namespace q3::bspstage {
namespace {

constexpr float kPlanarEpsilon = 0.5f;

// Non-planar surfaces take the first of these that every vertex normal faces.
constexpr Vec3 kAxisCandidates[6] = {{0, 0, -1}, {0, 0, 1}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};

}  // namespace

Vec3 lightmapAxisForNormal(const Vec3& n) {
    if (n == Vec3{0, 0, 0}) return n;
    const Vec3 a{std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
    // Negative axes are negated unit vectors (with -0 parts), as the .srf prints them.
    auto signedAxis = [](Vec3 axis, float component) { return component > 0 ? axis : -axis; };
    if (a.z > a.x - 0.0001f && a.z > a.y - 0.0001f) return signedAxis({0, 0, 1}, n.z);
    if (a.x > a.y - 0.0001f && a.x > a.z - 0.0001f) return signedAxis({1, 0, 0}, n.x);
    return signedAxis({0, 1, 0}, n.y);
}

void classifySurface(DrawSurface& ds, PlaneSet& planes, const ClassifyOptions& options) {
    if (ds.kind == SurfaceKind::Bad || ds.verts.empty()) return;
    const ShaderInfo& si = *ds.shader;
    if (ds.kind != SurfaceKind::Patch && ds.kind != SurfaceKind::Face && int(ds.verts.size()) > options.maxSurfaceVerts)
        ds.kind = SurfaceKind::ForcedMeta;

    Vec3 normal{0, 0, 0};
    float dist = 0;
    if (ds.planeNum >= 0) {
        normal = planes[ds.planeNum].normal().toFloat();
        dist = float(planes[ds.planeNum].dist());
    } else {
        for (const bsp::DrawVert& v : ds.verts) {
            const Vec3 n = Vec3::fromArray(v.normal);
            if (n == Vec3{0, 0, 0}) continue;
            normal = n;
            dist = dot(Vec3::fromArray(v.xyz), n);
            break;
        }
    }
    if (length(normal) == 0) {
        ds.planar = false;
        ds.planeNum = -1;
    } else {
        ds.planar = std::all_of(ds.verts.begin(), ds.verts.end(), [&](const bsp::DrawVert& v) {
            return std::fabs(dot(Vec3::fromArray(v.xyz), normal) - dist) <= kPlanarEpsilon;
        });
    }
    if (ds.planar) {
        if (ds.planeNum < 0) {
            const DVec3 first(Vec3::fromArray(ds.verts[0].xyz));
            ds.planeNum = planes.find({DVec3(normal), double(dist)}, std::span(&first, 1));
        }
        ds.planeNormal = normal;
    } else {
        ds.planeNum = -1;
        ds.planeNormal = {0, 0, 0};
    }

    if (si.isVertexLit() || ds.kind == SurfaceKind::Triangles) {
        ds.lightmapAxis = {0, 0, 0};
        ds.sampleSize = 0;
        return;
    }
    if (si.lightmapAxis >= 0) {
        ds.lightmapAxis = {0, 0, 0};
        ds.lightmapAxis[si.lightmapAxis] = 1;
    } else if (ds.kind == SurfaceKind::ForcedMeta) {
        ds.lightmapAxis = {0, 0, 0};
    } else if (ds.planar) {
        ds.lightmapAxis = lightmapAxisForNormal(normal);
    } else {
        for (const Vec3& axis : kAxisCandidates) {
            const bool facing = std::all_of(ds.verts.begin(), ds.verts.end(), [&](const bsp::DrawVert& v) {
                return dot(Vec3::fromArray(v.normal), axis) >= 0.25f;
            });
            if (facing) {
                ds.lightmapAxis = axis;
                break;
            }
        }
    }
    if (si.lightmapSampleSize > 0)
        ds.sampleSize = si.lightmapSampleSize;
    else if (ds.sampleSize <= 0)
        ds.sampleSize = options.sampleSize;
    if (ds.lightmapScale > 0) {
        ds.sampleSize = int(ds.lightmapScale * float(ds.sampleSize));
        ds.lightmapScale = 0;  // applied once, however often the surface is classified
    }
    ds.sampleSize = std::clamp(ds.sampleSize, std::max(options.minSampleSize, 1), 16384);
}

void biasSurfaceTextures(DrawSurface& ds) {
    if (ds.shader->globalTexture || ds.verts.empty()) return;
    float mins[2] = {999999, 999999}, maxs[2] = {-999999, -999999};
    for (const bsp::DrawVert& v : ds.verts)
        for (int i = 0; i < 2; ++i) {
            mins[i] = std::min(mins[i], v.st[i]);
            maxs[i] = std::max(maxs[i], v.st[i]);
        }
    float bias[2];
    for (int i = 0; i < 2; ++i) bias[i] = std::floor(0.5f * (mins[i] + maxs[i]));
    for (bsp::DrawVert& v : ds.verts)
        for (int i = 0; i < 2; ++i) v.st[i] -= bias[i];
}

}  // namespace q3::bspstage
