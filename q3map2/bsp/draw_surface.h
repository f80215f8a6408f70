// Draw surfaces while -bsp builds them (q3map2 mapDrawSurface_t): brush faces and patches with
// their vertices, what later steps add (fog number, triangles, lightmap projection), and where they
// came from, until they are filtered into the tree and written as BSP surfaces.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "bspfile.h"
#include "dvec3.h"
#include "vec3.h"

namespace q3 {
struct ShaderInfo;
}

namespace q3::bspstage {

struct IndexMap;

inline Vec3 xyzOf(const bsp::DrawVert& v) { return Vec3::fromArray(v.xyz); }
inline Vec3 normalOf(const bsp::DrawVert& v) { return Vec3::fromArray(v.normal); }

// Normalises in place and returns the length before; a zero vector is left alone (returns 0).
inline float normalizeInPlace(Vec3& v) {
    const float len = length(v);
    if (len == 0) return 0;
    v = v * (1.0f / len);
    return len;
}

// q3map2's surface types, in its order (the .srf comment names them).
enum class SurfaceKind { Bad, Face, Patch, Triangles, Flare, Foliage, ForcedMeta, Meta, Foghull, Decal, Shader };

std::string_view surfaceKindName(SurfaceKind kind);  // "ESurfaceType::Face", as q3map2's .srf writes it

inline constexpr int kNoFog = -1;

// A brush side a surface was drawn from (q3map2 sideRef_t), by its brush's index in the entity's
// list; the reversed copy of a fog face has no side of its own (see DrawSurface::fogBackFace).
struct SideRef {
    int brush = -1;
    int side = -1;
    bool fogBackFace = false;
};

struct DrawSurface {
    SurfaceKind kind = SurfaceKind::Face;
    const ShaderInfo* shader = nullptr;
    int mapEntityNum = 0;     // .map entity of the brush or patch (.srf "entity")
    int brush = -1;           // faces: brush (index in the entity's list) and side they come from
    int side = -1;
    bool fogBackFace = false;  // the reversed copy of a fog brush face: no brush side stands behind it
    int planeNum = -1;        // map plane of a planar surface, else -1
    bool planar = false;
    int fogNum = kNoFog;
    std::vector<bsp::DrawVert> verts;
    std::vector<int> indexes;  // triangles; empty for faces until they are triangulated, and for patches
    std::vector<bool> tjunctionVerts;  // faces: which vertices T-junction fixing added (empty: none)

    // Patches.
    int patchWidth = 0;
    int patchHeight = 0;
    DBounds lodBounds;         // control points of the patch's level-of-detail group
    float longestCurve = 0;

    // Flares: where the corona is, its colour and light style.
    Vec3 flareOrigin{0, 0, 0};
    Vec3 flareColor{0, 0, 0};
    int lightStyle = 0;

    // Lighting attributes (.srf and the surface record).
    Vec3 planeNormal{0, 0, 0};   // lightmapVecs[2]: the normal of a planar surface
    Vec3 lightmapAxis{0, 0, 0};
    int sampleSize = 0;          // entity _lightmapsamplesize until classified, then the final size
    float lightmapScale = 0;     // entity _lightmapscale, applied when classified
    int castShadows = 1;
    int receiveShadows = 1;

    float shadeAngle = 0;        // entity _shadeangle in degrees: meta triangles smooth their normals
    // The misc_model .map entity a model surface came from (-1 for others): its _ambient/_color and
    // _celshader apply in place of those of the entity the surface belongs to.
    int modelEntity = -1;
    std::vector<SideRef> metaSides;  // meta surfaces: the sides their triangles came from
    uint32_t extraSurfaceFlags = 0;  // added to the shader's in the BSP (-patchmeta collision patches)
    const ShaderInfo* celShader = nullptr;  // copied as a cel surface (entity _celshader, -celshader)
    bool backSide = false;                  // a q3map_backShader copy: written facing the other way

    int outputNum = -1;  // BSP surface number once written

    // _skybox: a surface drawn in a _skybox leaf gets a copy moved into the sky (skyboxCopy), drawn
    // where sky is; the copy names the original's BSP surface (.srf "parent").
    bool skybox = false;
    bool skyboxCopy = false;
    int parentSurface = -1;
};

// Lighting keys of a .map entity that every surface of its brushes and patches carries (q3map2
// ParseMapEntity): the world and func_groups cast and receive shadows, other entities only receive.
struct EntitySurfaceParams {
    int castShadows = 1;
    int receiveShadows = 1;
    int sampleSize = 0;       // _lightmapsamplesize / _samplesize / _ss
    float lightmapScale = 0;  // lightmapscale / _lightmapscale / _ls
    float shadeAngle = 0;     // _shadeangle / _smoothnormals / _sn / _sa / _smooth (degrees)
    // _color (zero or missing: white) x _ambient / ambient: the ambient light -light gives the
    // entity's lightmaps and vertexes (the .srf ambientColor; the worldspawn's is the default block's).
    Vec3 ambientColor{0, 0, 0};
    const IndexMap* indexMap = nullptr;  // _indexmap: layers its q3map_indexed faces and patches
};

}  // namespace q3::bspstage
