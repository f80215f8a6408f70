#include "foliage.h"

#include <array>

#include "float_plane.h"
#include "log.h"
#include "meta/patch_meta.h"
#include "patch.h"
#include "patch_surfaces.h"
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

// q3map2's older patch tessellation (SubdivideMesh with error 8 and span 512): each span of three
// points along the width is split in two (two columns inserted, the peak replaced) while, in some
// row, its middle point lies more than `maxError` from the blend of the three or one of its halves
// is longer than `maxSpan`, re-testing the first half; then the same down the height. Returns the
// grid, `width` and `height` updated.
std::vector<bsp::DrawVert> subdivideByError(const DrawSurface& patch, int& width, int& height) {
    constexpr float kMaxError = 8, kMaxSpan = 512;
    constexpr int kMaxAxis = patch::kMaxExpandedAxis;
    width = patch.patchWidth;
    height = patch.patchHeight;
    std::vector<std::vector<bsp::DrawVert>> grid = std::vector<std::vector<bsp::DrawVert>>(size_t(height));  // grid[row][column]
    for (int y = 0; y < height; ++y)
        grid[size_t(y)].assign(patch.verts.begin() + y * width, patch.verts.begin() + (y + 1) * width);
    // Splits along one axis; `at(line, k)` is the k-th point of a line across that axis.
    auto splitAxis = [&](int& count, int lines, auto&& at, auto&& insertPair) {
        for (int j = 0; j + 2 < count; j += 2) {
            int line = 0;
            for (; line < lines; ++line) {
                const Vec3 a = xyzOf(at(line, j)), b = xyzOf(at(line, j + 1)), c = xyzOf(at(line, j + 2));
                if (length(b - a) > kMaxSpan || length(c - b) > kMaxSpan) break;
                const Vec3 blend = (a + b * 2 + c) * 0.25f;
                if (length(b - blend) > kMaxError) break;
            }
            if (count + 2 >= kMaxAxis) break;
            if (line == lines) continue;
            count += 2;
            std::vector<std::array<bsp::DrawVert, 3>> added;  // all read before anything moves
            for (int l = 0; l < lines; ++l) {
                const bsp::DrawVert prev = midpoint(at(l, j), at(l, j + 1));
                const bsp::DrawVert next = midpoint(at(l, j + 1), at(l, j + 2));
                added.push_back({prev, midpoint(prev, next), next});
            }
            for (int l = 0; l < lines; ++l) insertPair(l, j, added[size_t(l)][0], added[size_t(l)][1], added[size_t(l)][2]);
            j -= 2;
        }
    };
    splitAxis(
        width, height, [&](int row, int k) -> bsp::DrawVert& { return grid[size_t(row)][size_t(k)]; },
        [&](int row, int j, const bsp::DrawVert& prev, const bsp::DrawVert& mid, const bsp::DrawVert& next) {
            std::vector<bsp::DrawVert>& r = grid[size_t(row)];
            r[size_t(j + 1)] = prev;
            r.insert(r.begin() + j + 2, {mid, next});
        });
    splitAxis(
        height, width, [&](int column, int k) -> bsp::DrawVert& { return grid[size_t(k)][size_t(column)]; },
        [&](int column, int j, const bsp::DrawVert& prev, const bsp::DrawVert& mid, const bsp::DrawVert& next) {
            if (column == 0) grid.insert(grid.begin() + j + 2, 2, std::vector<bsp::DrawVert>(size_t(width)));
            grid[size_t(j + 1)][size_t(column)] = prev;
            grid[size_t(j + 2)][size_t(column)] = mid;
            grid[size_t(j + 3)][size_t(column)] = next;
        });
    std::vector<bsp::DrawVert> out;
    for (const std::vector<bsp::DrawVert>& row : grid) out.insert(out.end(), row.begin(), row.end());
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
    if (!triangles && source.kind != SurfaceKind::Patch) return;  // brush faces need -meta
    // Patches are scattered over their older, error-driven tessellation, on the curve, without
    // straight rows and columns.
    std::vector<bsp::DrawVert> verts = source.verts;
    std::vector<int> indexes = source.indexes;
    if (source.kind == SurfaceKind::Patch) {
        int width = 0, height = 0;
        verts = subdivideByError(source, width, height);
        putGridOnCurve(verts, width, height);
        patch::PatchMesh mesh = meta::asPatchMesh(verts, width, height);
        patch::removeLinearRowsColumns(mesh);
        verts.clear();
        for (const patch::PatchVertex& p : mesh.verts) verts.push_back(meta::drawVert(p));
        indexes.assign(mesh.indices.begin(), mesh.indices.end());
    }
    for (const ShaderFoliage& foliage : source.shader->foliage) {
        std::vector<Instance> instances;
        Scatter s{foliage, in.random, instances};
        for (size_t i = 0; i + 2 < indexes.size(); i += 3)
            scatterOnTriangle(s, {&verts[size_t(indexes[i])], &verts[size_t(indexes[i + 1])], &verts[size_t(indexes[i + 2])]});
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
