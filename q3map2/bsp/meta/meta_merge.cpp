#include "meta_merge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "shader_info.h"

namespace q3::bspstage::meta {
namespace {

constexpr int kAxisScore = 100000;
constexpr int kVertScore = 10000;
constexpr int kSurfaceScore = 1000;
constexpr int kStScore = 50;
constexpr int kDefaultAdequate = kAxisScore + kVertScore;
constexpr int kDefaultGood = kAxisScore + 2 * kVertScore + 4 * kStScore;
constexpr int kDefaultLightmapSize = 128;  // q3map2's lightmap page width without q3map_lightmapSize

constexpr float kBig = std::numeric_limits<float>::max();

struct Box {
    Vec3 mins{kBig, kBig, kBig};
    Vec3 maxs{-kBig, -kBig, -kBig};
    void add(const Vec3& p) {
        for (int i = 0; i < 3; ++i) {
            mins[i] = std::min(mins[i], p[i]);
            maxs[i] = std::max(maxs[i], p[i]);
        }
    }
    bool surrounds(const Box& o) const {
        for (int i = 0; i < 3; ++i)
            if (o.mins[i] < mins[i] || o.maxs[i] > maxs[i]) return false;
        return true;
    }
};

// Within `distance` of the box on every axis.
bool near(const Box& b, const Vec3& p, float distance) {
    for (int i = 0; i < 3; ++i)
        if (p[i] < b.mins[i] - distance || p[i] > b.maxs[i] + distance) return false;
    return true;
}

// How a triangle would join the surface: each corner's vertex (an existing one, or -1 for new).
struct Placement {
    int score = 0;
    std::array<int, 3> existing{-1, -1, -1};
    Box bounds;
    Box texBounds;
};

// One meta surface while it grows (q3map2 MetaTrianglesToSurface's drawsurface and its tables).
class Growing {
public:
    Growing(const MetaTriangles& set, const MetaTriangle& seed, const PlaneSet& planes, const TextureSizes& textures,
            const MergeLimits& limits, MergeCounts& counts)
        : set_(set), limits_(limits), counts_(counts), seedSurface_(seed.surfaceNum) {
        ds.kind = SurfaceKind::Meta;
        ds.shader = seed.shader;
        ds.mapEntityNum = seed.entityNum;
        ds.castShadows = seed.castShadows;
        ds.receiveShadows = seed.receiveShadows;
        ds.planeNum = seed.planeNum;
        ds.fogNum = seed.fogNum;
        ds.sampleSize = seed.sampleSize;
        ds.shadeAngle = seed.shadeAngle;
        ds.modelEntity = seed.modelEntity;
        ds.lightmapAxis = seed.lightmapAxis;
        vertexLit_ = seed.shader->isVertexLit();
        maxVerts_ = vertexLit_ ? limits.maxSurfaceVerts : limits.maxLightmappedVerts;
        lightmapWidth_ = seed.shader->lightmapWidth > 0 ? seed.shader->lightmapWidth : kDefaultLightmapSize;
        const TextureSize size = textures.of(*seed.shader);
        texWidth_ = float(size.width);
        texHeight_ = float(size.height);
        samePlaneOnly_ = limits.npDegrees == 0 && !seed.shader->nonplanar && seed.planeNum >= 0;
        if (samePlaneOnly_) {
            planeNormal_ = planes[seed.planeNum].normal().toFloat();
            planeDist_ = float(planes[seed.planeNum].dist());
        }
    }

    // The triangle's score, 0 when it cannot join (q3map2 AddMetaTriangleToSurface).
    Placement place(const MetaTriangle& t) const {
        Placement p;
        if (samePlaneOnly_) {
            if (t.planeNum >= 0 && t.planeNum != ds.planeNum) return p;
            if (!nearlyEqual(planeNormal_, t.normal) || planeDist_ != t.dist) return p;
        }
        if (limits_.maxBBoxDistance >= 0 && !ds.indexes.empty() &&
            std::none_of(t.verts.begin(), t.verts.end(), [&](int v) {
                return near(bounds_, xyzOf(set_.vertices[size_t(v)].vert), limits_.maxBBoxDistance);
            }))
            return p;
        int score = t.surfaceNum == seedSurface_ ? kSurfaceScore : 0;
        if (vertexLit_ || nearlyEqual(ds.lightmapAxis, t.lightmapAxis))
            score += kAxisScore;
        else
            score = int(float(score) + float(kAxisScore) * dot(ds.lightmapAxis, t.normal));

        int coincident = 0, added = 0;
        for (int k = 0; k < 3; ++k) {
            const bsp::DrawVert& v = set_.vertices[size_t(t.verts[size_t(k)])].vert;
            p.existing[size_t(k)] = findVertex(v, coincident);
            if (p.existing[size_t(k)] < 0 && int(ds.verts.size()) + added++ >= maxVerts_) return p;
        }
        score += coincident * kVertScore;

        p.bounds = bounds_;
        p.texBounds = texBounds_;
        for (int v : t.verts) {
            const bsp::DrawVert& dv = set_.vertices[size_t(v)].vert;
            p.bounds.add(xyzOf(dv));
            p.texBounds.add({dv.st[0], dv.st[1], 0});
        }
        if (!vertexLit_ && !ds.indexes.empty() && ds.lightmapAxis != Vec3{0, 0, 0} &&
            (!nearlyEqual(bounds_.mins, p.bounds.mins) || !nearlyEqual(bounds_.maxs, p.bounds.maxs))) {
            const float lightmapMax = float(ds.sampleSize * (lightmapWidth_ - 1));
            for (int i = 0; i < 3; ++i)
                if (p.bounds.maxs[i] - p.bounds.mins[i] > lightmapMax) return p;
        }
        if (ds.verts.empty() || texBounds_.surrounds(p.texBounds)) {
            score += 4 * kStScore;
        } else {
            const int oldS = int((texBounds_.maxs[0] - texBounds_.mins[0]) * texWidth_);
            const int oldT = int((texBounds_.maxs[1] - texBounds_.mins[1]) * texHeight_);
            const int newS = int((p.texBounds.maxs[0] - p.texBounds.mins[0]) * texWidth_);
            const int newT = int((p.texBounds.maxs[1] - p.texBounds.mins[1]) * texHeight_);
            if (newS <= oldS)
                score += 2 * kStScore;
            else if (oldT > oldS)
                score += kStScore;
            if (newT <= oldT)
                score += 2 * kStScore;
            else if (oldS > oldT)
                score += kStScore;
        }
        if (int(ds.indexes.size()) + 3 > limits_.maxIndexes) return p;
        p.score = score;
        return p;
    }

    void add(const MetaTriangle& t, const Placement& p) {
        const int before = int(ds.verts.size());
        for (int k = 0; k < 3; ++k) {
            int index = p.existing[size_t(k)];
            if (index < 0) {
                index = int(ds.verts.size());
                ds.verts.push_back(set_.vertices[size_t(t.verts[size_t(k)])].vert);
            }
            ds.indexes.push_back(index);
        }
        bounds_ = p.bounds;
        texBounds_ = p.texBounds;
        ds.metaSides.push_back(t.side);
        for (int i = before; i < int(ds.verts.size()); ++i) {
            const float key = spatialDistance(xyzOf(ds.verts[size_t(i)]));
            sorted_.insert(std::upper_bound(sorted_.begin(), sorted_.end(), key,
                                            [](float k, const std::pair<float, int>& e) { return k < e.first; }),
                           {key, i});
        }
    }

    DrawSurface ds;

private:
    // The surface vertex a corner can reuse (same position and normal within 0.001, texture
    // coordinates within 1e-4, same alpha), or -1; counts the corners with the same position and
    // normal seen on the way (q3map2 AddMetaVertToSurface).
    int findVertex(const bsp::DrawVert& v, int& coincident) const {
        const float key = spatialDistance(xyzOf(v));
        auto it = std::lower_bound(sorted_.begin(), sorted_.end(), key - kSpatialEpsilon,
                                   [](const std::pair<float, int>& e, float k) { return e.first < k; });
        for (; it != sorted_.end() && it->first <= key + kSpatialEpsilon; ++it) {
            const bsp::DrawVert& s = ds.verts[size_t(it->second)];
            if (!nearlyEqual(xyzOf(v), xyzOf(s)) || !nearlyEqual(normalOf(v), normalOf(s))) continue;
            ++coincident;
            if (std::fabs(v.st[0] - s.st[0]) >= 1e-4f || std::fabs(v.st[1] - s.st[1]) >= 1e-4f) continue;
            if (v.color[3] != s.color[3]) continue;
            ++counts_.mergedVerts;
            return it->second;
        }
        return -1;
    }

    const MetaTriangles& set_;
    const MergeLimits& limits_;
    MergeCounts& counts_;
    int seedSurface_;
    bool vertexLit_ = false;
    int maxVerts_ = 64;
    int lightmapWidth_ = kDefaultLightmapSize;
    float texWidth_ = 64, texHeight_ = 64;
    bool samePlaneOnly_ = false;
    Vec3 planeNormal_{0, 0, 0};
    float planeDist_ = 0;
    Box bounds_;
    Box texBounds_;
    std::vector<std::pair<float, int>> sorted_;  // vertices by spatial distance, equal keys in order
};

// The triangles that may join the surface next: those touching it (a corner at one of its corner
// positions) with the seed's merge keys, in the order they were found (q3map2's test cloud).
class Cloud {
public:
    explicit Cloud(size_t triangleCount) : stamp_(triangleCount, -1) {}

    void start(int surface) {
        surface_ = surface;
        list_.clear();
    }

    // Adds the untouched triangles at the corners of `t`, then marks `t` used.
    void expand(MetaTriangles& set, int t) {
        const MetaTriangle& tri = set.triangles[size_t(t)];
        for (int corner : tri.verts)
            for (int v : set.groups[size_t(set.vertices[size_t(corner)].group)])
                for (int other : set.vertices[size_t(v)].triangles) {
                    const MetaTriangle& o = set.triangles[size_t(other)];
                    if (o.used || stamp_[size_t(other)] == surface_ || !o.mergeableWith(tri)) continue;
                    stamp_[size_t(other)] = surface_;
                    list_.push_back(other);
                }
        set.triangles[size_t(t)].used = true;
        // Used triangles are skipped while scanning; drop them once they dominate the list.
        if (++usedInList_ * 2 > list_.size() + 16) {
            std::erase_if(list_, [&](int i) { return set.triangles[size_t(i)].used; });
            usedInList_ = 0;
        }
    }

    const std::vector<int>& list() const { return list_; }

private:
    std::vector<int> stamp_;  // the surface whose cloud holds the triangle
    std::vector<int> list_;
    int surface_ = -1;
    size_t usedInList_ = 0;
};

// q3map2's processing order: merge keys, then position along the oblique direction. q3map2 orders
// shaders by address, that is by the order it made them: script shaders in load order, then the
// others as the map first used them (here: as the triangles first use them).
std::vector<int> processingOrder(const MetaTriangles& set, const ShaderTable* table) {
    std::map<const ShaderInfo*, int> shaderRank;
    if (table) {
        std::map<const ShaderInfo*, int> loaded;
        for (const auto& s : table->shaders()) loaded.emplace(s.get(), int(loaded.size()));
        for (const MetaTriangle& t : set.triangles) {
            if (shaderRank.contains(t.shader)) continue;
            auto it = loaded.find(t.shader);
            // A layer shader of indexed terrain is a copy: it ranks as the script shader it copies.
            if (it == loaded.end()) it = loaded.find(table->findExplicit(t.shader->name));
            if (it != loaded.end()) shaderRank.emplace(t.shader, it->second);
        }
    }
    const int firstUnloaded = table ? int(table->size()) : 0;
    for (const MetaTriangle& t : set.triangles)
        if (!shaderRank.contains(t.shader)) shaderRank.emplace(t.shader, firstUnloaded + int(shaderRank.size()));
    std::vector<int> order(set.triangles.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int ia, int ib) {
        const MetaTriangle& a = set.triangles[size_t(ia)];
        const MetaTriangle& b = set.triangles[size_t(ib)];
        if (a.shader != b.shader) return shaderRank.at(a.shader) < shaderRank.at(b.shader);
        if (a.fogNum != b.fogNum) return a.fogNum < b.fogNum;
        if (a.entityNum != b.entityNum) return a.entityNum < b.entityNum;
        if (a.castShadows != b.castShadows) return a.castShadows < b.castShadows;
        if (a.receiveShadows != b.receiveShadows) return a.receiveShadows < b.receiveShadows;
        if (a.sampleSize != b.sampleSize) return a.sampleSize < b.sampleSize;
        return a.spatialMin < b.spatialMin;
    });
    return order;
}

}  // namespace

std::vector<DrawSurface> mergeMetaTriangles(MetaTriangles& set, const PlaneSet& planes, const TextureSizes& textures,
                                            const MergeLimits& limits, MergeCounts* counts, const ShaderTable* table) {
    MergeCounts local;
    MergeCounts& c = counts ? *counts : local;
    const int adequate = limits.adequateScore >= 0 ? limits.adequateScore : kDefaultAdequate;
    const int good = limits.goodScore >= 0 ? limits.goodScore : kDefaultGood;
    std::vector<DrawSurface> out;
    Cloud cloud(set.triangles.size());
    for (int seed : processingOrder(set, table)) {
        if (set.triangles[size_t(seed)].used) continue;
        Growing surface(set, set.triangles[size_t(seed)], planes, textures, limits, c);
        cloud.start(int(out.size()));
        const Placement first = surface.place(set.triangles[size_t(seed)]);
        if (first.score > 0) surface.add(set.triangles[size_t(seed)], first);
        cloud.expand(set, seed);
        while (true) {
            int best = -1, bestScore = 0;
            for (int t : cloud.list()) {
                if (set.triangles[size_t(t)].used) continue;
                const int score = surface.place(set.triangles[size_t(t)]).score;
                if (score > bestScore) {
                    best = t;
                    bestScore = score;
                    // Adding a good one at once lets the candidates it brings compete next round.
                    if (bestScore >= good) break;
                }
            }
            if (best < 0 || bestScore <= adequate) break;
            const Placement p = surface.place(set.triangles[size_t(best)]);
            if (p.score > 0) {
                surface.add(set.triangles[size_t(best)], p);
                cloud.expand(set, best);
            }
        }
        out.push_back(std::move(surface.ds));
        ++c.surfaces;
    }
    return out;
}

}  // namespace q3::bspstage::meta
