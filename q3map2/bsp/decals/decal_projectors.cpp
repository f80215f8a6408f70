#include "decals.h"

#include <cmath>
#include <string>

#include "count_line.h"
#include "log.h"
#include "map_file.h"
#include "patch.h"
#include "patch_surfaces.h"
#include "script.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

// The entity whose targetname equals `target` exactly, first in file order; func_groups are gone
// by now. An empty target names the first entity without a targetname, as in q3map2.
const map::MapEntity* targetEntity(const map::MapFile& file, const std::string& target) {
    for (const map::MapEntity& e : file.entities) {
        const std::string_view classname = e.classname();
        if (equalsNoCase(classname, "func_group") || equalsNoCase(classname, "group_info")) continue;
        if (e.value("targetname") == target) return &e;
    }
    return nullptr;
}

struct Corner {
    Vec3 xyz;
    float st[2];
};

// The linear map from positions to texture coordinates that reproduces the triangle's st when the
// triangle is flattened onto the projection plane; false when its st are degenerate.
bool makeTextureMatrix(DecalProjector& dp, const FPlane& projection, const Corner& a, const Corner& b,
                       const Corner& c) {
    auto flatten = [&](const Vec3& p) { return DVec3(p - projection.normal * projection.distanceTo(p)); };
    const DVec3 pa = flatten(a.xyz), pb = flatten(b.xyz), pc = flatten(c.xyz);
    const double bb = (double(b.st[0]) - a.st[0]) * (double(c.st[1]) - a.st[1]) -
                      (double(c.st[0]) - a.st[0]) * (double(b.st[1]) - a.st[1]);
    if (std::fabs(bb) < 0.00000001) return false;
    // Where texture coordinates (s, t) lie on the flattened triangle, by barycentric weights.
    auto pointAt = [&](double s, double t) {
        const double w0 = ((b.st[0] - s) * (c.st[1] - t) - (c.st[0] - s) * (b.st[1] - t)) / bb;
        const double w1 = ((c.st[0] - s) * (a.st[1] - t) - (a.st[0] - s) * (c.st[1] - t)) / bb;
        const double w2 = ((a.st[0] - s) * (b.st[1] - t) - (b.st[0] - s) * (a.st[1] - t)) / bb;
        return pa * w0 + pb * w1 + pc * w2;
    };
    const DVec3 steps[2] = {pointAt(a.st[0] + 1.0, a.st[1] + 0.0) - pa, pointAt(a.st[0] + 0.0, a.st[1] + 1.0) - pa};
    for (int i = 0; i < 2; ++i) {
        // One unit of s (or t) per step length along the step's direction.
        const double len = length(steps[i]);
        const DVec3 axis = len == 0 ? DVec3{} : steps[i] * (1.0 / len);
        const Vec3 row = len != 0 ? (axis * (1.0 / len)).toFloat() : Vec3{0, 0, 0};
        dp.texMat[i][0] = row.x;
        dp.texMat[i][1] = row.y;
        dp.texMat[i][2] = row.z;
        dp.texMat[i][3] = a.st[i] - dot(a.xyz, row);
    }
    return true;
}

// A prism from the triangle swept `distance` along the projection; false when a plane or the
// texture matrix cannot be made.
bool makeProjector(DecalProjector& dp, const ShaderInfo* shader, const FPlane& projection, float distance,
                   const Corner (&v)[3]) {
    dp = DecalProjector{};
    dp.shader = shader;
    dp.numPlanes = 3 + 2;
    if (!makeTextureMatrix(dp, projection, v[0], v[1], v[2])) return false;
    const Vec3 sweep = projection.normal * distance;
    Bounds bounds;
    for (const Corner& c : v) {
        bounds.add(c.xyz);
        bounds.add(c.xyz + sweep);
    }
    dp.mins = bounds.mins;
    dp.maxs = bounds.maxs;
    dp.center = (dp.mins + dp.maxs) * 0.5f;
    dp.radius = length(dp.maxs - dp.center);
    if (!floatPlaneFromPoints(dp.planes[0], v[0].xyz, v[1].xyz, v[2].xyz)) return false;
    dp.planes[1].normal = -dp.planes[0].normal;
    dp.planes[1].dist = dot(v[0].xyz + sweep, dp.planes[1].normal);
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        if (!floatPlaneFromPoints(dp.planes[i + 2], v[j].xyz, v[i].xyz, v[i].xyz + sweep)) return false;
    }
    return true;
}

}  // namespace

void collectDecalEntities(LoadedMap& map, const map::MapFile& file, Log& log) {
    for (BspEntity& e : map.entities) {
        if (!equalsNoCase(e.classname, "_decal")) continue;
        if (e.patches.empty()) {
            log.warning("Decal entity without any patch meshes, ignoring.");
            continue;
        }
        const map::MapEntity* target = targetEntity(file, e.source->value("target"));
        if (!target) {
            log.warning("Decal entity without a valid target, ignoring.");
            continue;
        }
        DecalEntity decal;
        decal.mapEntityNum = e.mapEntityNum;
        decal.origin = e.origin;
        decal.target = parseVectorKey(target->value("origin"));
        for (const Brush& b : e.brushes) decal.bounds.add(b.bounds);
        for (const PatchRef& ref : e.patches)
            if (!isDegeneratePatch(*ref.patch))
                for (const map::PatchControl& c : ref.patch->control) decal.bounds.add(DVec3(c.xyz));
        decal.patches = std::move(e.patches);
        e.patches.clear();
        map.decals.push_back(std::move(decal));
    }
}

std::vector<DecalProjector> makeDecalProjectors(const LoadedMap& map, const ShaderTable& shaders,
                                                int patchSubdivisions, Log& log) {
    log.debug("--- ProcessDecals ---");
    std::vector<DecalProjector> projectors;
    bool warned = false;
    for (const DecalEntity& decal : map.decals) {
        const Vec3 entityOrigin = decal.origin.toFloat();
        for (const PatchRef& ref : decal.patches) {
            const map::MapPatch& p = *ref.patch;
            if (isDegeneratePatch(p)) continue;  // q3map2 never keeps such a patch
            // Without an origin key, projection starts from the centre of the whole entity.
            Vec3 origin = entityOrigin;
            if (decal.origin == DVec3{}) origin = (decal.bounds.mins.toFloat() + decal.bounds.maxs.toFloat()) * 0.5f;
            FPlane projection;
            double distance = 0;
            projection.normal = normalizedLikeQ3map2(decal.target.toFloat() - origin, &distance);
            projection.dist = dot(origin, projection.normal);
            if (float(distance) <= 0.125f) continue;

            const patch::PatchMesh mesh =
                patch::tessellateForLighting(patchControlGrid(p), patchLongestCurve(p), patchSubdivisions);
            const ShaderInfo* shader = &shaders.find(map::shaderNameForTexture(p.texture));
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                Corner v[3];
                for (int k = 0; k < 3; ++k) {
                    const patch::PatchVertex& pv = mesh.verts[mesh.indices[i + size_t(k)]];
                    v[k] = {pv.xyz + entityOrigin, {pv.st[0], pv.st[1]}};
                }
                if (int(projectors.size()) >= kMaxDecalProjectors) {
                    if (!warned)
                        log.warning("MAX_PROJECTORS (" + std::to_string(kMaxDecalProjectors) +
                                    ") exceeded, no more decal projectors available.");
                    warned = true;
                    continue;
                }
                DecalProjector dp;
                if (makeProjector(dp, shader, projection, float(distance), v)) projectors.push_back(dp);
            }
        }
    }
    log.debug(countLine(int(projectors.size()), "decal projectors"));
    return projectors;
}

}  // namespace q3::bspstage
