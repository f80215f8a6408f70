#include "face_surfaces.h"

#include <algorithm>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "index_map.h"
#include "script.h"
#include "shader_info.h"
#include "terrain_shaders.h"
#include "texture_projection.h"

namespace q3::bspstage {
namespace {

constexpr double kCullEpsilon = 0.1;
constexpr double kEqualEpsilon = 0.001;  // q3map2 VectorCompare

bool vectorsEqual(const DVec3& a, const DVec3& b, double epsilon) {
    return std::fabs(a.x - b.x) <= epsilon && std::fabs(a.y - b.y) <= epsilon && std::fabs(a.z - b.z) <= epsilon;
}

// q3map2 SideInBrush: a side lying on or behind every plane of an opaque brush without nodraw
// sides is hidden, unless its shader is an autosprite or polygonOffset one.
void cullIfInside(BrushSide& side, const Brush& other, const PlaneSet& planes, CullCounts& counts) {
    if (side.winding.empty() || !side.shader) return;
    if (side.culled || (other.compileFlags & compileflags::Translucent)) return;
    for (const BrushSide& s : other.sides) {
        if (s.compileFlags & compileflags::NoDraw) return;
        const PlaneSide where = windingOnPlaneSide(side.winding, planes[s.planeNum].plane);
        if (where == PlaneSide::Front || where == PlaneSide::Cross) return;
        // A side just culled on the same plane facing the same way does not hide this one.
        if (where == PlaneSide::On && s.culled && dot(planes[side.planeNum].normal(), planes[s.planeNum].normal()) > 0)
            return;
    }
    if (side.shader->autosprite || side.shader->polygonOffset) return;
    side.culled = true;
    ++counts.hidden;
}

// The point of `b` matching a[0], and the direction b runs in to match a[1]; 0 when none.
bool sameWindings(const Winding& a, const Winding& b) {
    const int n = int(a.size());
    int first = -1;
    for (int k = 0; k < n; ++k)
        if (vectorsEqual(a[0], b[size_t(k)], kEqualEpsilon)) {
            first = k;
            break;
        }
    if (first < 0) return false;
    int dir = 0;
    if (vectorsEqual(a[1], b[size_t((first + 1) % n)], kCullEpsilon))
        dir = 1;
    else if (vectorsEqual(a[1], b[size_t((first + n - 1) % n)], kCullEpsilon))
        dir = -1;
    if (dir == 0) return false;
    for (int k = 0, l = first; k < n; ++k, l = (l + dir + n) % n)
        if (!vectorsEqual(a[size_t(k)], b[size_t(l)], kCullEpsilon)) return false;
    return true;
}

bool hidesOthers(const BrushSide& s) {
    return !s.culled && !(s.compileFlags & compileflags::Translucent) && !(s.compileFlags & compileflags::NoDraw);
}

bool neverCulled(const BrushSide& s) { return s.shader->autosprite || s.shader->polygonOffset; }

// Of two faces with the same winding on the same plane pair, the one the other covers goes.
void cullCoincident(Brush& a, Brush& b, CullCounts& counts) {
    for (BrushSide& s1 : a.sides) {
        if (s1.winding.empty() || !s1.shader) continue;
        for (BrushSide& s2 : b.sides) {
            if (s2.winding.empty() || !s2.shader || s1.winding.size() != s2.winding.size()) continue;
            if (s1.culled && s2.culled) continue;
            if ((s1.planeNum & ~1) != (s2.planeNum & ~1)) continue;
            if (neverCulled(s1) || neverCulled(s2)) continue;
            if (!sameWindings(s1.winding, s2.winding)) continue;
            if (hidesOthers(s2)) {
                s1.culled = true;
                ++counts.coincident;
            }
            if (s1.planeNum == s2.planeNum && s1.culled) continue;
            if (hidesOthers(s1)) {
                s2.culled = true;
                ++counts.coincident;
            }
        }
    }
}

int intKey(const map::MapEntity& e, std::initializer_list<const char*> keys, int fallback) {
    for (const char* k : keys)
        if (const std::string* v = e.find(k)) return std::atoi(v->c_str());
    return fallback;
}

double floatKey(const map::MapEntity& e, std::initializer_list<const char*> keys) {
    for (const char* k : keys)
        if (const std::string* v = e.find(k)) return std::atof(v->c_str());
    return 0;
}

// q3map2 snaps brush face vertices to 1/8 unit so that neighbouring faces meet exactly.
double snapEighth(double v) { return std::floor(v * 8.0 + 0.5) / 8.0; }

}  // namespace

CullCounts cullSides(std::vector<Brush>& brushes, const PlaneSet& planes) {
    CullCounts counts;
    for (size_t i = 0; i < brushes.size(); ++i) {
        Brush& a = brushes[i];
        if (a.sides.empty()) continue;
        for (size_t j = i + 1; j < brushes.size(); ++j) {
            Brush& b = brushes[j];
            if (b.sides.empty() || !a.bounds.intersects(b.bounds)) continue;
            for (BrushSide& s : a.sides) cullIfInside(s, b, planes, counts);
            for (BrushSide& s : b.sides) cullIfInside(s, a, planes, counts);
            cullCoincident(a, b, counts);
        }
    }
    return counts;
}

EntitySurfaceParams entitySurfaceParams(const map::MapEntity& entity, bool worldGroup) {
    EntitySurfaceParams p;
    p.castShadows = intKey(entity, {"_castShadows", "_cs"}, worldGroup ? 1 : 0);
    p.receiveShadows = intKey(entity, {"_receiveShadows", "_rs"}, 1);
    p.sampleSize = std::max(0, intKey(entity, {"_lightmapsamplesize", "_samplesize", "_ss"}, 0));
    p.lightmapScale = float(std::max(0.0, floatKey(entity, {"lightmapscale", "_lightmapscale", "_ls"})));
    p.shadeAngle = float(std::max(0.0, floatKey(entity, {"_shadeangle", "_smoothnormals", "_sn", "_sa", "_smooth"})));
    Vec3 color = parseVectorKey(entity.value("_color")).toFloat();
    if (length(color) == 0) color = {1, 1, 1};
    p.ambientColor = color * float(floatKey(entity, {"_ambient", "ambient"}));
    return p;
}

std::vector<EntitySurfaceParams> entitySurfaceParams(const map::MapFile& map) {
    std::vector<EntitySurfaceParams> out;
    for (const map::MapEntity& e : map.entities)
        out.push_back(entitySurfaceParams(e, e.number == 0 || equalsNoCase(e.classname(), "func_group")));
    return out;
}

DrawSurface faceSurface(const BspEntity& entity, int brushIndex, int sideIndex, const Winding& winding,
                        const EntitySurfaceParams& params, const FaceContext& context, bool backFace) {
    const Brush& brush = entity.brushes[size_t(brushIndex)];
    const BrushSide& side = brush.sides[size_t(sideIndex)];
    // Each vertex takes its layer from the index map where the winding lies, before snapping.
    std::optional<LayeredVertices> layers;
    const ShaderInfo* layerShader = nullptr;
    if (params.indexMap && side.shader->indexed && context.terrain) {
        std::vector<Vec3> points;
        for (const DVec3& p : winding) points.push_back(p.toFloat());
        layers = params.indexMap->layer(points);
        layerShader = &context.terrain->layerShader(*side.shader, params.indexMap->layerShaderName(*layers));
    }
    const ShaderInfo& shader = layerShader ? *layerShader : *side.shader;
    const int planeNum = backFace ? side.planeNum ^ 1 : side.planeNum;
    const MapPlane& plane = context.planes[planeNum];

    DrawSurface ds;
    ds.kind = SurfaceKind::Face;
    ds.shader = &shader;
    ds.mapEntityNum = brush.mapEntityNum;
    ds.brush = brushIndex;
    ds.side = sideIndex;
    ds.fogBackFace = backFace;
    ds.planar = true;
    ds.planeNum = planeNum;
    ds.planeNormal = plane.normal().toFloat();
    ds.castShadows = params.castShadows;
    ds.receiveShadows = params.receiveShadows;
    ds.sampleSize = params.sampleSize;
    ds.lightmapScale = params.lightmapScale;
    ds.shadeAngle = params.shadeAngle;

    const TextureSize size = layerShader ? context.terrain->sizeOf(shader) : context.textures.of(shader);
    const std::optional<GeneratedProjection> generated = generatedProjection(shader, size);
    map::TextureVecs vecs;
    if (!generated && side.face) {
        // The projection belongs to the side as the map wrote it, also on a fog face's back copy.
        const MapPlane& sidePlane = context.planes[side.planeNum];
        map::MapPlane mapPlane;
        for (int i = 0; i < 3; ++i) mapPlane.normal[i] = sidePlane.normal()[i];
        mapPlane.dist = sidePlane.dist();
        // The shift was reduced by the side's own shader when the map was read (q3map2 ParseRawBrush).
        const TextureSize own = layerShader ? context.textures.of(*side.shader) : size;
        vecs = map::textureVectors(*side.face, mapPlane,
                                   {size.width, size.height, side.shader->globalTexture, own.width, own.height});
    }
    ds.verts.reserve(winding.size());
    for (size_t i = 0; i < winding.size(); ++i) {
        bsp::DrawVert dv{};
        DVec3 xyz = roundToFloat(winding[i]);
        if (layers) xyz.z = double(float(xyz.z) + layers->zOffset[i]);
        if (context.brushSnap) xyz = {snapEighth(xyz.x), snapEighth(xyz.y), snapEighth(xyz.z)};
        xyz = roundToFloat(xyz);
        xyz.toFloat().toArray(dv.xyz);
        // Textures stay where the map put them when an origin brush moved the entity's brushes.
        const Vec3 world = (xyz + entity.originBrushCenter).toFloat();
        if (generated) {
            dv.st[0] = dot(generated->s, world);
            dv.st[1] = dot(generated->t, world);
        } else {
            dv.st[0] = float(vecs.s(world));
            dv.st[1] = float(vecs.t(world));
        }
        ds.planeNormal.toArray(dv.normal);
        for (uint8_t& c : dv.color) c = 255;
        if (layers) dv.color[3] = layers->alpha[i];
        ds.verts.push_back(dv);
    }
    return ds;
}

namespace {

// -skyfix (q3map2 DrawSurfaceForSide, DrawSurfaceForShader): a face of a skyParms shader makes
// the game load the six box images through shader-only surfaces, one per image in the BSP.
void addSkyFixSurfaces(const ShaderInfo& sky, const FaceContext& context, std::vector<DrawSurface>& out) {
    if (!context.skyFixShaders || sky.skyParmsEnv.empty()) return;
    for (const char* suffix : {"_lf", "_rt", "_ft", "_bk", "_up", "_dn"}) {
        const ShaderInfo& image = context.skyFixShaders->find(sky.skyParmsEnv + suffix);
        auto uses = [&](const DrawSurface& ds) { return ds.shader == &image; };
        if (std::any_of(out.begin(), out.end(), uses)) continue;
        if (context.earlierSurfaces &&
            std::any_of(context.earlierSurfaces->begin(), context.earlierSurfaces->end(),
                        [&](const std::unique_ptr<DrawSurface>& ds) { return uses(*ds); }))
            continue;
        DrawSurface ds;
        ds.kind = SurfaceKind::Shader;
        ds.shader = &image;
        ds.castShadows = 0;  // q3map2 leaves these surfaces' lighting keys zero
        ds.receiveShadows = 0;
        out.push_back(std::move(ds));
    }
}

}  // namespace

void addFaceSurfaces(const BspEntity& entity, const FaceContext& context,
                     const std::vector<EntitySurfaceParams>& paramsByMapEntity, std::vector<DrawSurface>& out) {
    for (size_t b = 0; b < entity.brushes.size(); ++b) {
        const Brush& brush = entity.brushes[b];
        const EntitySurfaceParams& params = paramsByMapEntity[size_t(brush.mapEntityNum)];
        for (size_t s = 0; s < brush.sides.size(); ++s) {
            const BrushSide& side = brush.sides[s];
            if (side.winding.empty() || side.visibleHull.empty() || !side.shader || side.culled) continue;
            const ShaderInfo& shader = *side.shader;
            const bool fog = (shader.compileFlags & compileflags::Fog) != 0;
            // Indexed terrain shaders are often nodraw: their faces take a layer shader instead.
            if (shader.isNoDraw() && !fog && !shader.indexed) continue;
            const Winding& w = shader.autosprite || shader.noClip ? side.winding : side.visibleHull;
            addSkyFixSurfaces(shader, context, out);
            out.push_back(faceSurface(entity, int(b), int(s), w, params, context));
            if (fog) {
                // The inside of a fog volume is seen from within: a flipped copy of the face.
                out.push_back(faceSurface(entity, int(b), int(s), reverseWinding(w), params, context, true));
            }
        }
    }
}

}  // namespace q3::bspstage
