#include "foliage.h"

#include <array>

#include "float_plane.h"
#include "log.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

struct Instance {
    Vec3 xyz;
    Vec3 normal;
};

struct Scatter {
    const ShaderFoliage& foliage;
    LibcRandom& random;
    std::vector<Instance>& instances;
};

// q3map2's Random(): rand() over RAND_MAX, in floats.
float randomUnit(LibcRandom& random) { return float(random.next()) / float(2147483647); }

// Halfway between two vertices; a normal that cancels out keeps the first one's.
bsp::DrawVert midpoint(const bsp::DrawVert& a, const bsp::DrawVert& b) {
    bsp::DrawVert out{};
    for (int k = 0; k < 3; ++k) out.xyz[k] = (a.xyz[k] + b.xyz[k]) * 0.5f;
    for (int k = 0; k < 2; ++k) {
        out.st[k] = (a.st[k] + b.st[k]) * 0.5f;
        out.lightmap[k] = (a.lightmap[k] + b.lightmap[k]) * 0.5f;
    }
    for (int k = 0; k < 4; ++k) out.color[k] = uint8_t((a.color[k] + b.color[k]) >> 1);
    double len = 0;
    const Vec3 n = normalizedLikeQ3map2(normalOf(a) + normalOf(b), &len);
    (len == 0 ? normalOf(a) : n).toArray(out.normal);
    return out;
}

using Corners = std::array<const bsp::DrawVert*, 3>;

void scatterOnTriangle(Scatter& s, const Corners& tri) {
    if (int(s.instances.size()) >= kMaxFoliageInstances) return;
    FPlane plane;
    if (!floatPlaneFromPoints(plane, xyzOf(*tri[0]), xyzOf(*tri[1]), xyzOf(*tri[2]))) return;
    if (plane.normal.z < 0.5f) return;  // too steep for anything to stand on

    int longest = -1;
    float longestSquared = 0;
    Vec3 centre{0, 0, 0}, normal{0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        const Vec3 edge = xyzOf(*tri[size_t(i)]) - xyzOf(*tri[size_t((i + 1) % 3)]);
        const float squared = dot(edge, edge);
        if (squared > longestSquared) {
            longestSquared = squared;
            longest = i;
        }
        centre += xyzOf(*tri[size_t(i)]);
        normal += normalOf(*tri[size_t(i)]);
    }
    if (longestSquared <= s.foliage.density * s.foliage.density) {
        float alpha = 1.0f;
        if (s.foliage.inverseAlpha != 2) {
            alpha = float(tri[0]->color[3] + tri[1]->color[3] + tri[2]->color[3]) / 765.0f;
            if (s.foliage.inverseAlpha == 1) alpha = 1.0f - alpha;
            if (alpha < 0.75f) return;
        }
        if (randomUnit(s.random) > s.foliage.odds * alpha) return;
        double len = 0;
        const Vec3 n = normalizedLikeQ3map2(normal, &len);
        if (len == 0) return;
        s.instances.push_back({centre * 0.33333333f, n});
        return;
    }
    // Halve the longest edge and scatter on both halves.
    const bsp::DrawVert mid = midpoint(*tri[size_t(longest)], *tri[size_t((longest + 1) % 3)]);
    Corners first = tri, second = tri;
    first[size_t(longest)] = &mid;
    second[size_t((longest + 1) % 3)] = &mid;
    scatterOnTriangle(s, first);
    scatterOnTriangle(s, second);
}

}  // namespace

void addFoliage(const DrawSurface& source, FoliageInputs& in, std::vector<DrawSurface>& out, Log& log) {
    if (source.shader->foliage.empty()) return;
    const bool triangles = source.kind == SurfaceKind::Meta || source.kind == SurfaceKind::ForcedMeta ||
                           source.kind == SurfaceKind::Triangles;
    if (source.kind == SurfaceKind::Patch) {
        log.warning("shader " + source.shader->name +
                    ": q3map_foliage on patches is not supported by this build; the patch gets no foliage");
        return;
    }
    if (!triangles) return;  // q3map2 scatters only over triangles (brush faces need -meta)
    for (const ShaderFoliage& foliage : source.shader->foliage) {
        std::vector<Instance> instances;
        Scatter s{foliage, in.random, instances};
        for (size_t i = 0; i + 2 < source.indexes.size(); i += 3)
            scatterOnTriangle(s, {&source.verts[size_t(source.indexes[i])], &source.verts[size_t(source.indexes[i + 1])],
                                  &source.verts[size_t(source.indexes[i + 2])]});
        if (instances.empty()) continue;
        for (DrawSurface& ds : scaledModelSurfaces(foliage.model, foliage.scale, in.models, in.map,
                                                   "shader " + source.shader->name + " q3map_foliage", log)) {
            ds.kind = SurfaceKind::Foliage;
            ds.mapEntityNum = in.mapEntityNum;
            ds.castShadows = source.castShadows;
            ds.receiveShadows = source.receiveShadows;
            ds.lightmapScale = source.lightmapScale;
            ds.fogNum = source.fogNum;
            // The instance count and the model's vertex count travel in the patch size fields.
            ds.patchWidth = int(instances.size());
            ds.patchHeight = int(ds.verts.size());
            for (const Instance& fi : instances) {
                bsp::DrawVert v{};
                fi.xyz.toArray(v.xyz);
                fi.normal.toArray(v.normal);
                v.color[0] = v.color[1] = v.color[2] = v.color[3] = 255;
                ds.verts.push_back(v);
            }
            out.push_back(std::move(ds));
        }
    }
}

}  // namespace q3::bspstage
