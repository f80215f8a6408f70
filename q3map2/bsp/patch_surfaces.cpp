#include "patch_surfaces.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "index_map.h"
#include "log.h"
#include "patch.h"
#include "shader_info.h"
#include "terrain_shaders.h"

namespace q3::bspstage {
namespace {

constexpr float kEqualEpsilon = 0.001f;  // q3map2 EQUAL_EPSILON

bool nearlyEqual(Vec3 a, Vec3 b) {
    return std::fabs(a.x - b.x) <= kEqualEpsilon && std::fabs(a.y - b.y) <= kEqualEpsilon &&
           std::fabs(a.z - b.z) <= kEqualEpsilon;
}

// q3map2's length estimate of the quadratic span a-b-c, walked in eight float steps exactly as it
// does (the .srf prints all digits); 0 for a straight span or one with a leg under 1/8 unit.
float spanLength(Vec3 a, Vec3 b, Vec3 c) {
    Vec3 ab = b - a, bc = c - b, ac = c - a;
    if (normalizeInPlace(ab) < 0.125f || normalizeInPlace(bc) < 0.125f || normalizeInPlace(ac) < 0.125f) return 0;
    if (dot(ab, bc) > 0.99f && dot(ab, ac) > 0.99f) return 0;
    ab = b - a;
    bc = c - b;
    Vec3 last = a;
    float len = 0, t = 0;
    for (int i = 0; i < 8; ++i, t += 1.0f / 8) {
        const Vec3 point = a + (ab * (1.0f - t) + bc * t);
        len += length(point - last);
        last = point;
    }
    return len;
}

}  // namespace

float patchLongestCurve(const map::MapPatch& p) {
    float longest = 0;
    for (int x = 0; x + 2 < p.width; x += 2)
        for (int y = 0; y + 2 < p.height; y += 2) {
            longest = std::max(longest, spanLength(p.at(x, y).xyz, p.at(x + 1, y).xyz, p.at(x + 2, y).xyz));
            longest = std::max(longest, spanLength(p.at(x, y).xyz, p.at(x, y + 1).xyz, p.at(x, y + 2).xyz));
        }
    return longest;
}

patch::ControlGrid patchControlGrid(const map::MapPatch& p) {
    patch::ControlGrid g;
    g.width = p.width;
    g.height = p.height;
    for (const map::PatchControl& c : p.control) {
        patch::PatchVertex v;
        v.xyz = c.xyz;
        v.st[0] = c.st[0];
        v.st[1] = c.st[1];
        g.points.push_back(v);
    }
    return g;
}

void makeGridNormals(std::vector<bsp::DrawVert>& verts, int width, int height) {
    static constexpr int kNeighbours[8][2] = {{0, 1}, {1, 1}, {1, 0}, {1, -1}, {0, -1}, {-1, -1}, {-1, 0}, {-1, 1}};
    auto at = [&](int x, int y) -> bsp::DrawVert& { return verts[size_t(y) * size_t(width) + size_t(x)]; };
    bool wrapWidth = true, wrapHeight = true;
    for (int y = 0; y < height && wrapWidth; ++y)
        if (length(xyzOf(at(0, y)) - xyzOf(at(width - 1, y))) > 1.0f) wrapWidth = false;
    for (int x = 0; x < width && wrapHeight; ++x)
        if (length(xyzOf(at(x, 0)) - xyzOf(at(x, height - 1))) > 1.0f) wrapHeight = false;

    std::vector<Vec3> normals(verts.size());
    for (int x = 0; x < width; ++x) {
        for (int y = 0; y < height; ++y) {
            const Vec3 base = xyzOf(at(x, y));
            Vec3 around[8];
            bool good[8] = {};
            for (int k = 0; k < 8; ++k) {
                for (int dist = 1; dist <= 3; ++dist) {
                    int nx = x + kNeighbours[k][0] * dist, ny = y + kNeighbours[k][1] * dist;
                    if (wrapWidth) nx = nx < 0 ? width - 1 + nx : (nx >= width ? 1 + nx - width : nx);
                    if (wrapHeight) ny = ny < 0 ? height - 1 + ny : (ny >= height ? 1 + ny - height : ny);
                    if (nx < 0 || nx >= width || ny < 0 || ny >= height) break;  // the patch's edge
                    Vec3 d = xyzOf(at(nx, ny)) - base;
                    if (normalizeInPlace(d) == 0) continue;  // coincident point: look further
                    good[k] = true;
                    around[k] = d;
                    break;
                }
            }
            Vec3 sum{0, 0, 0};
            for (int k = 0; k < 8; ++k) {
                if (!good[k] || !good[(k + 1) & 7]) continue;
                Vec3 n = cross(around[(k + 1) & 7], around[k]);
                if (normalizeInPlace(n) == 0) continue;
                sum += n;
            }
            normalizeInPlace(sum);
            normals[size_t(y) * size_t(width) + size_t(x)] = sum;
        }
    }
    for (size_t i = 0; i < verts.size(); ++i) normals[i].toArray(verts[i].normal);
}

void putGridOnCurve(std::vector<bsp::DrawVert>& verts, int width, int height) {
    auto blend = [](const bsp::DrawVert& prev, bsp::DrawVert& mid, const bsp::DrawVert& next) {
        for (int i = 0; i < 3; ++i) mid.xyz[i] = (prev.xyz[i] + mid.xyz[i] * 2 + next.xyz[i]) * 0.25f;
        for (int i = 0; i < 2; ++i) {
            mid.st[i] = (prev.st[i] + mid.st[i] * 2 + next.st[i]) * 0.25f;
            mid.lightmap[i] = (prev.lightmap[i] + mid.lightmap[i] * 2 + next.lightmap[i]) * 0.25f;
        }
    };
    auto at = [&](int x, int y) -> bsp::DrawVert& { return verts[size_t(y) * size_t(width) + size_t(x)]; };
    for (int x = 0; x < width; ++x)
        for (int y = 1; y < height; y += 2) blend(at(x, y - 1), at(x, y), at(x, y + 1));
    for (int y = 0; y < height; ++y)
        for (int x = 1; x < width; x += 2) blend(at(x - 1, y), at(x, y), at(x + 1, y));
}

bool isDegeneratePatch(const map::MapPatch& patch) {
    const size_t n = patch.control.size();
    Vec3 first{0, 0, 0};
    size_t i = 1;
    for (; i < n; ++i) {
        first = patch.control[0].xyz - patch.control[i].xyz;
        if (normalizeInPlace(first) != 0) break;
    }
    if (i >= n) return true;
    for (size_t j = 1; j < n; ++j) {
        Vec3 d = patch.control[0].xyz - patch.control[j].xyz;
        if (normalizeInPlace(d) == 0) continue;
        if (!nearlyEqual(first, d) && !nearlyEqual(first, -d)) return false;
    }
    return true;
}

namespace {

// After the plane is found (from the unmoved control points): the layer shader and alphas of an
// index-mapped patch, the shader's generated texture projection, then the layers' height offsets.
void applyPatchShading(DrawSurface& ds, const BspEntity& entity, const EntitySurfaceParams& params,
                       TerrainShaders* terrain) {
    std::optional<LayeredVertices> layers;
    if (params.indexMap && ds.shader->indexed && terrain) {
        std::vector<Vec3> points;
        for (const bsp::DrawVert& dv : ds.verts) points.push_back(xyzOf(dv));
        layers = params.indexMap->layer(points);
        ds.shader = &terrain->layerShader(*ds.shader, params.indexMap->layerShaderName(*layers));
    }
    const std::optional<GeneratedProjection> generated =
        terrain ? terrain->projectionOf(*ds.shader) : generatedProjection(*ds.shader, kDefaultTextureSize);
    for (size_t v = 0; v < ds.verts.size(); ++v) {
        bsp::DrawVert& dv = ds.verts[v];
        if (generated) {
            const Vec3 world = xyzOf(dv) + entity.origin.toFloat();
            dv.st[0] = dot(generated->s, world);
            dv.st[1] = dot(generated->t, world);
        }
        if (!layers) continue;
        dv.color[3] = layers->alpha[v];
        dv.xyz[2] += layers->zOffset[v];
    }
}

}  // namespace

std::vector<DrawSurface> patchSurfaces(const BspEntity& entity, const ShaderTable& shaders, PlaneSet& planes,
                                       const std::vector<EntitySurfaceParams>& paramsByMapEntity, Log& log,
                                       PatchCounts* counts, TerrainShaders* terrain) {
    std::vector<const PatchRef*> kept;
    for (const PatchRef& ref : entity.patches) {
        if (isDegeneratePatch(*ref.patch)) {
            log.warning("Entity " + std::to_string(ref.mapEntityNum) + ", Brush " +
                        std::to_string(ref.patch->primitiveNum) + ": degenerate patch");
            continue;
        }
        kept.push_back(&ref);
    }
    std::vector<patch::ControlGrid> grids;
    for (const PatchRef* ref : kept) grids.push_back(patchControlGrid(*ref->patch));
    // Patches sharing a control point pick their level of detail together: every member gets the
    // group's control point bounds and longest curve.
    const std::vector<int> groups = patch::patchLodGroups(grids);
    std::vector<DBounds> groupBounds;
    std::vector<float> groupCurve;
    for (size_t i = 0; i < kept.size(); ++i) {
        const size_t g = size_t(groups[i]);
        if (g >= groupBounds.size()) {
            groupBounds.resize(g + 1);
            groupCurve.resize(g + 1, 0.0f);
        }
        for (const map::PatchControl& c : kept[i]->patch->control) groupBounds[g].add(DVec3(c.xyz));
        groupCurve[g] = std::max(groupCurve[g], patchLongestCurve(*kept[i]->patch));
    }

    std::vector<DrawSurface> out;
    for (size_t i = 0; i < kept.size(); ++i) {
        const map::MapPatch& p = *kept[i]->patch;
        const EntitySurfaceParams& params = paramsByMapEntity[size_t(kept[i]->mapEntityNum)];
        DrawSurface ds;
        ds.kind = SurfaceKind::Patch;
        ds.shader = &shaders.find(map::shaderNameForTexture(p.texture));
        ds.mapEntityNum = kept[i]->mapEntityNum;
        ds.patchWidth = p.width;
        ds.patchHeight = p.height;
        ds.lodBounds = groupBounds[size_t(groups[i])];
        ds.longestCurve = groupCurve[size_t(groups[i])];
        ds.castShadows = params.castShadows;
        ds.receiveShadows = params.receiveShadows;
        ds.sampleSize = params.sampleSize;
        ds.lightmapScale = params.lightmapScale;
        ds.shadeAngle = params.shadeAngle;
        for (const map::PatchControl& c : p.control) {
            bsp::DrawVert dv{};
            c.xyz.toArray(dv.xyz);
            dv.st[0] = c.st[0];
            dv.st[1] = c.st[1];
            for (uint8_t& col : dv.color) col = 255;
            ds.verts.push_back(dv);
        }
        // Normals from the control net, replaced by those of the net moved onto the curve where
        // the two disagree (degenerate or folded edges).
        makeGridNormals(ds.verts, p.width, p.height);
        std::vector<bsp::DrawVert> onCurve = ds.verts;
        putGridOnCurve(onCurve, p.width, p.height);
        makeGridNormals(onCurve, p.width, p.height);
        for (size_t v = 0; v < ds.verts.size(); ++v)
            if (dot(normalOf(onCurve[v]), normalOf(ds.verts[v])) < 0.75f)
                std::copy(onCurve[v].normal, onCurve[v].normal + 3, ds.verts[v].normal);

        const Vec3 normal = normalOf(ds.verts[0]);
        const float dist = dot(xyzOf(ds.verts[0]), normal);
        if (length(normal) < 0.001f) log.info("DrawSurfaceForMesh: bogus plane");
        bool planar = true;
        for (size_t v = 1; v < ds.verts.size() && planar; ++v)
            planar = nearlyEqual(normal, normalOf(ds.verts[v])) &&
                     std::fabs(dot(xyzOf(ds.verts[v]), normal) - dist) <= kEqualEpsilon;
        if (planar) {
            const DVec3 point(xyzOf(ds.verts[0]));
            ds.planeNum = planes.find({DVec3(normal), double(dist)}, std::span(&point, 1));
            ds.planar = ds.planeNum >= 0;
            ds.planeNormal = normal;
            for (bsp::DrawVert& dv : ds.verts) normal.toArray(dv.normal);
        }
        applyPatchShading(ds, entity, params, terrain);
        out.push_back(std::move(ds));
    }
    if (counts) {
        counts->patches = int(kept.size());
        counts->lodGroups = groups.empty() ? 0 : *std::max_element(groups.begin(), groups.end()) + 1;
    }
    return out;
}

}  // namespace q3::bspstage
