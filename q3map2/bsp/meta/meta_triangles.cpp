#include "meta_triangles.h"

#include <cmath>
#include <cstdio>

#include "log.h"
#include "shader_info.h"
#include "surface_classify.h"

namespace q3::bspstage::meta {
namespace {

constexpr float kMinEdge = 0.125f;  // shorter edges make a triangle degenerate

// Unit axis of a shader's q3map_lightmapAxis (0 x, 1 y, 2 z).
Vec3 shaderAxis(int axis) {
    Vec3 v{0, 0, 0};
    v[axis] = 1;
    return v;
}

std::string corner(const bsp::DrawVert& v) {
    char text[64];
    std::snprintf(text, sizeof text, "(%6.0f %6.0f %6.0f)", v.xyz[0], v.xyz[1], v.xyz[2]);
    return text;
}

}  // namespace

float spatialDistance(const Vec3& p) {
    constexpr float nx = 0.786868f, ny = 0.316861f, nz = 0.529564f;
    return p.x * nx + p.y * ny + p.z * nz;
}

bool nearlyEqual(const Vec3& a, const Vec3& b) {
    return std::fabs(a.x - b.x) < kEqualEpsilon && std::fabs(a.y - b.y) < kEqualEpsilon &&
           std::fabs(a.z - b.z) < kEqualEpsilon;
}

bool sameVertex(const bsp::DrawVert& a, const bsp::DrawVert& b) {
    return nearlyEqual(xyzOf(a), xyzOf(b)) && nearlyEqual(normalOf(a), normalOf(b)) &&
           std::fabs(a.st[0] - b.st[0]) < 1e-4f && std::fabs(a.st[1] - b.st[1]) < 1e-4f && a.color[3] == b.color[3];
}

int MetaTriangles::findOrInsert(const bsp::DrawVert& v) {
    const float d = spatialDistance(xyzOf(v));
    const auto begin = groupsByDistance_.lower_bound(d - kSpatialEpsilon);
    const auto end = groupsByDistance_.upper_bound(d + kSpatialEpsilon);
    for (auto it = begin; it != end; ++it)
        for (int index : groups[size_t(it->second)])
            if (sameVertex(v, vertices[size_t(index)].vert)) return index;
    const int index = int(vertices.size());
    for (auto it = begin; it != end; ++it) {
        std::vector<int>& group = groups[size_t(it->second)];
        if (nearlyEqual(xyzOf(v), xyzOf(vertices[size_t(group.front())].vert))) {
            vertices.push_back({v, it->second, {}});
            group.push_back(index);
            return index;
        }
    }
    const int group = int(groups.size());
    groups.push_back({index});
    vertices.push_back({v, group, {}});
    groupsByDistance_.emplace_hint(begin, d, group);
    return index;
}

void MetaTriangles::insert(MetaTriangle t, std::array<bsp::DrawVert, 3> c, const PlaneSet& planes, Log& log) {
    for (int i = 0; i < 3; ++i)
        if (length(xyzOf(c[size_t(i)]) - xyzOf(c[size_t((i + 1) % 3)])) < kMinEdge) return;
    if (t.planeNum >= 0) {
        // Small triangles give poor planes: the surface's own plane is used when it has one.
        t.normal = planes[t.planeNum].normal().toFloat();
        t.dist = float(planes[t.planeNum].dist());
    } else {
        const DVec3 a(xyzOf(c[0])), b(xyzOf(c[1])), e(xyzOf(c[2]));
        const DVec3 n = cross(e - a, b - a);
        const double len = length(n);
        if (len == 0) return;
        t.normal = (n / len).toFloat();
        t.dist = float(dot(a, n / len));
    }
    for (bsp::DrawVert& v : c)
        if (length(normalOf(v)) == 0) t.normal.toArray(v.normal);
    if (!t.shader->isVertexLit() && t.lightmapAxis == Vec3{0, 0, 0})
        t.lightmapAxis = t.shader->lightmapAxis >= 0 ? shaderAxis(t.shader->lightmapAxis) : lightmapAxisForNormal(t.normal);
    for (int i = 0; i < 3; ++i) t.verts[size_t(i)] = findOrInsert(c[size_t(i)]);

    // The same three vertices already make a triangle with the same merge keys: a duplicate (or
    // the same triangle facing the other way).
    const MetaVertex& v0 = vertices[size_t(t.verts[0])];
    const MetaVertex& v1 = vertices[size_t(t.verts[1])];
    const MetaVertex& v2 = vertices[size_t(t.verts[2])];
    if (!v0.triangles.empty() && !v1.triangles.empty() && !v2.triangles.empty()) {
        for (int t0 : v0.triangles) {
            const bool shared = std::find(v1.triangles.begin(), v1.triangles.end(), t0) != v1.triangles.end() &&
                                std::find(v2.triangles.begin(), v2.triangles.end(), t0) != v2.triangles.end();
            if (shared && t.mergeableWith(triangles[size_t(t0)])) {
                log.warning("Duplicate or Flipped triangle: " + corner(c[0]) + " " + corner(c[1]) + " " + corner(c[2]));
                ++duplicates;
                return;
            }
        }
    }
    const int index = int(triangles.size());
    t.spatialMin = std::min({spatialDistance(xyzOf(v0.vert)), spatialDistance(xyzOf(v1.vert)),
                             spatialDistance(xyzOf(v2.vert))});
    triangles.push_back(t);
    for (int v : t.verts) vertices[size_t(v)].triangles.push_back(index);
}

void MetaTriangles::addSurface(const DrawSurface& ds, int surfaceNum, const PlaneSet& planes, Log& log) {
    if (ds.verts.size() < 3 || ds.indexes.size() < 3) return;
    MetaTriangle base;
    base.shader = ds.shader;
    base.side = {ds.brush, ds.side, ds.fogBackFace};
    base.entityNum = ds.mapEntityNum;
    base.surfaceNum = surfaceNum;
    base.planeNum = ds.planeNum;
    base.fogNum = ds.fogNum;
    base.sampleSize = ds.sampleSize;
    base.castShadows = ds.castShadows;
    base.receiveShadows = ds.receiveShadows;
    base.shadeAngle = ds.shadeAngle;
    base.modelEntity = ds.modelEntity;
    base.lightmapAxis = ds.lightmapAxis;
    for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) {
        const int a = ds.indexes[i], b = ds.indexes[i + 1], c = ds.indexes[i + 2];
        if (a == b || a == c || b == c) continue;
        insert(base, {ds.verts[size_t(a)], ds.verts[size_t(b)], ds.verts[size_t(c)]}, planes, log);
    }
}

}  // namespace q3::bspstage::meta
