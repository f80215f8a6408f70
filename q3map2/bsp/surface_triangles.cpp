#include "surface_triangles.h"

#include <algorithm>
#include <string>

#include "log.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

constexpr int kMaxStripIndexes = 1024;
constexpr int kVertexCacheSize = 16;

// The strip starting at vertex `first`, or nothing when one of its triangles is a sliver. The two
// ends walk towards each other; each step moves the end whose next vertex is a T-junction vertex,
// else they take turns.
std::vector<int> stripFrom(const DrawSurface& ds, int first) {
    const int n = int(ds.verts.size());
    auto wrap = [n](int i) { return i < 0 ? i + n : (i < n ? i : i - n); };
    auto isTJunction = [&](int i) { return !ds.tjunctionVerts.empty() && ds.tjunctionVerts[size_t(wrap(i))]; };
    auto xyz = [&](int i) { return xyzOf(ds.verts[size_t(i)]); };
    std::vector<int> out;
    int i = wrap(first), j = wrap(i - 1);
    bool swap = false;
    while (true) {
        swap ^= isTJunction(swap ? i + 1 : j - 1) >= isTJunction(swap ? j - 1 : i + 1);
        int k;
        if (swap) {
            k = j;
            j = wrap(j - 1);
        } else {
            k = i;
            i = wrap(i + 1);
        }
        if (i == j) break;
        if (triangleMinAngleSquaredSin(xyz(i), xyz(j), xyz(k)) <= 1e-5 || triangleArea2x(xyz(i), xyz(j), xyz(k)) <= 1.0)
            return {};
        out.insert(out.end(), {i, j, k});
    }
    return out;
}

void fanFace(DrawSurface& ds) {
    const size_t n = ds.verts.size();
    bsp::DrawVert centre{};
    Vec3 xyz{0, 0, 0}, normal{0, 0, 0};
    float st[2] = {0, 0}, lightmap[2] = {0, 0}, color[4] = {0, 0, 0, 0};
    for (const bsp::DrawVert& v : ds.verts) {
        xyz += xyzOf(v);
        normal += Vec3::fromArray(v.normal);
        for (int i = 0; i < 2; ++i) {
            st[i] += v.st[i];
            lightmap[i] += v.lightmap[i];
        }
        for (int i = 0; i < 4; ++i) color[i] += v.color[i];
    }
    const double inverse = 1.0 / double(n);
    (xyz * float(inverse)).toArray(centre.xyz);
    const float len = length(normal);
    (len == 0 ? Vec3::fromArray(ds.verts[0].normal) : normal * (1.0f / len)).toArray(centre.normal);
    for (int i = 0; i < 2; ++i) {
        centre.st[i] = float(st[i] * inverse);
        centre.lightmap[i] = float(lightmap[i] * inverse);
    }
    for (int i = 0; i < 4; ++i) centre.color[i] = uint8_t(std::clamp(color[i] / float(n), 0.0f, 255.0f));
    ds.verts.insert(ds.verts.begin(), centre);
    if (!ds.tjunctionVerts.empty()) ds.tjunctionVerts.insert(ds.tjunctionVerts.begin(), false);
    const int count = int(ds.verts.size());
    ds.indexes.clear();
    for (int i = 1; i < count; ++i) {
        const int next = (i + 1) % count;
        ds.indexes.insert(ds.indexes.end(), {0, i, next ? next : 1});
    }
}

}  // namespace

double triangleArea2x(const Vec3& a, const Vec3& b, const Vec3& c) { return length(cross(b - a, c - a)); }

double triangleMinAngleSquaredSin(const Vec3& a, const Vec3& b, const Vec3& c) {
    // The smallest angle faces the shortest edge: measure it between the two others.
    const Vec3 d[3] = {b - a, c - a, c - b};
    const double l[3] = {dot(d[0], d[0]), dot(d[1], d[1]), dot(d[2], d[2])};
    const int shortest = l[0] < l[1] ? (l[0] < l[2] ? 0 : 2) : (l[1] < l[2] ? 1 : 2);
    if (l[shortest] == 0) return 0;
    const int e1 = shortest == 2 ? 0 : shortest + 1;
    const int e2 = e1 == 2 ? 0 : e1 + 1;
    const Vec3 n = cross(d[e1], d[e2]);
    return double(dot(n, n)) / (l[e1] * l[e2]);
}

void triangulateFace(DrawSurface& ds, TriangulationCounts* counts) {
    const int n = int(ds.verts.size());
    if (n == 0) return;
    if (n == 3) {
        ds.indexes = {0, 1, 2};
        if (counts) ++counts->strips;
        return;
    }
    int least = 0;
    if (!ds.shader->autosprite) {
        for (int i = 0; i < n; ++i) {
            const float* v1 = ds.verts[size_t(i)].xyz;
            const float* v2 = ds.verts[size_t(least)].xyz;
            if (v1[0] < v2[0] || (v1[0] == v2[0] && v1[1] < v2[1]) || (v1[0] == v2[0] && v1[1] == v2[1] && v1[2] < v2[2]))
                least = i;
        }
    }
    const int wanted = (n - 2) * 3;
    if (wanted > kMaxStripIndexes)
        throw CompileError("face of shader " + ds.shader->name + " with " + std::to_string(n) +
                           " vertices needs more than " + std::to_string(kMaxStripIndexes) + " indexes");
    for (int r = 0; r < n; ++r) {
        std::vector<int> strip = stripFrom(ds, (r + least) % n);
        if (int(strip.size()) == wanted) {
            ds.indexes = std::move(strip);
            if (counts) ++counts->strips;
            return;
        }
    }
    fanFace(ds);
    if (counts) ++counts->fans;
}

void optimizeForVertexCache(std::vector<int>& indexes) {
    const int count = int(indexes.size());
    if (count <= kVertexCacheSize) return;
    std::vector<int> pool = indexes;
    int cache[kVertexCacheSize + 1];
    for (int i = 0; i <= kVertexCacheSize; ++i) cache[i] = i < count ? pool[size_t(i)] : 0;
    for (int i = 0; i < count; i += 3) {
        int first = -1, best = -1, bestScore = -1;
        for (int j = 0; j < count; j += 3) {
            if (pool[size_t(j)] == -1) continue;
            if (first < 0) first = j;
            int score = 0;
            for (int k = 0; k < kVertexCacheSize; ++k)
                if (pool[size_t(j)] == cache[k] || pool[size_t(j) + 1] == cache[k] || pool[size_t(j) + 2] == cache[k])
                    ++score;
            if (score > bestScore) {
                bestScore = score;
                best = j;
            }
            if (score == 3) break;
        }
        if (best < 0) best = first;
        if (best < 0) continue;
        for (int j = 0; j < 3; ++j) {
            const int index = pool[size_t(best + j)];
            if (std::find(cache, cache + kVertexCacheSize, index) != cache + kVertexCacheSize) continue;
            std::copy_backward(cache, cache + kVertexCacheSize, cache + kVertexCacheSize + 1);
            cache[0] = index;
        }
        int* tri = &indexes[size_t(i)];
        for (int j = 0; j < 3; ++j) {
            tri[j] = pool[size_t(best + j)];
            pool[size_t(best + j)] = -1;
        }
        while (tri[0] > tri[1] || tri[0] > tri[2]) std::rotate(tri, tri + 1, tri + 3);
    }
}

}  // namespace q3::bspstage
