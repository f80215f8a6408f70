// Meta triangles (q3map2 surface_meta.cpp metaTriangle_t, SurfaceToMetaTriangles): with -meta the
// triangles of an entity's faces (and of patches with -patchmeta, and forced-meta surfaces) are
// pooled, each carrying what decides whether two may share a surface (shader, fog, entity, shadow
// flags, sample size), its plane and lightmap axis. Vertices are pooled too: equal vertices (same
// position and normal within 0.001, texture coordinates within 1e-4, same alpha) are one, and all
// vertices at one position form a group, so that triangles meeting there can find each other.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "draw_surface.h"
#include "plane_set.h"

namespace q3 {
class Log;
}

namespace q3::bspstage::meta {

// q3map2 sorts and looks up meta vertices by their distance along this fixed oblique direction.
float spatialDistance(const Vec3& p);
inline constexpr float kEqualEpsilon = 0.001f;                // q3map2 EQUAL_EPSILON
inline constexpr float kSpatialEpsilon = 2 * kEqualEpsilon;  // look-up window along the direction

// Every component within 0.001 (q3map2 VectorCompare).
bool nearlyEqual(const Vec3& a, const Vec3& b);
// One meta vertex for both (q3map2 bspDrawVert_equal).
bool sameVertex(const bsp::DrawVert& a, const bsp::DrawVert& b);

struct MetaVertex {
    bsp::DrawVert vert;
    int group = -1;               // the vertices at this position
    std::vector<int> triangles;   // triangles using it, in insertion order
};

struct MetaTriangle {
    const ShaderInfo* shader = nullptr;
    SideRef side;
    int entityNum = 0;
    int surfaceNum = 0;  // the surface it came from: a surface prefers its own seed's triangles
    int planeNum = -1;
    int fogNum = kNoFog;
    int sampleSize = 0;
    int castShadows = 1;
    int receiveShadows = 1;
    float shadeAngle = 0;  // the entity's, in degrees
    int modelEntity = -1;  // the surface's, passed on to the meta surface it seeds
    Vec3 normal{0, 0, 0};  // plane, in single precision as q3map2 keeps it
    float dist = 0;
    Vec3 lightmapAxis{0, 0, 0};
    std::array<int, 3> verts{};
    float spatialMin = 0;  // smallest spatialDistance of its corners (the merge order)
    bool used = false;     // merged into a surface

    // Whether the two may share a surface (q3map2 CompareMetaTriangles::equal).
    bool mergeableWith(const MetaTriangle& o) const {
        return shader == o.shader && fogNum == o.fogNum && entityNum == o.entityNum &&
               castShadows == o.castShadows && receiveShadows == o.receiveShadows && sampleSize == o.sampleSize;
    }
};

class MetaTriangles {
public:
    // Adds the triangles of a triangulated, classified surface (q3map2 SurfaceToMetaTriangles).
    // Triangles with a repeated index or an edge under 0.125 are dropped, so is one equal to an
    // existing triangle on the same three vertices (warned about, as q3map2 does).
    void addSurface(const DrawSurface& ds, int surfaceNum, const PlaneSet& planes, Log& log);

    std::vector<MetaVertex> vertices;
    std::vector<std::vector<int>> groups;  // vertex indexes at one position, in order of arrival
    std::vector<MetaTriangle> triangles;
    int duplicates = 0;

private:
    void insert(MetaTriangle t, std::array<bsp::DrawVert, 3> corners, const PlaneSet& planes, Log& log);
    int findOrInsert(const bsp::DrawVert& v);

    // Groups by the spatial distance of their first vertex (q3map2's multimap: equal keys keep
    // the order they were put in, a new one goes before them).
    std::multimap<float, int> groupsByDistance_;
};

}  // namespace q3::bspstage::meta
