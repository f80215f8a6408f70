#include "bsp_tree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

namespace q3::light {

bool shaderIsTranslucent(const bsp::Shader& shader) {
    using namespace contents;
    // The content flags the C_TRANSLUCENT surfaceparms of q3map2's quake3 game table set.
    constexpr int32_t kTranslucentContents = kLava | kSlime | kWater | kAreaPortal | kPlayerClip | kMonsterClip |
                                             kClusterPortal | kDoNotEnter | kBotClip | kOrigin | kTranslucent |
                                             kTrigger | kNoDrop;
    constexpr int32_t kTranslucentSurface = kSurfLightFilter | kSurfAlphaShadow;
    return (shader.contentFlags & kTranslucentContents) != 0 || (shader.surfaceFlags & kTranslucentSurface) != 0;
}

BspTree::BspTree(const bsp::Bsp& bsp, std::span<const uint8_t> translucentShaders) : bsp_(bsp) {
    opaque_.assign(bsp.brushes.size(), 0);
    if (!bsp.models.empty()) {
        // Only world brushes block light in q3map2's point-in-solid test.
        const bsp::Model& world = bsp.models[0];
        for (int i = 0; i < world.numBrushes; ++i) {
            const int b = world.firstBrush + i;
            if (b < 0 || b >= int(bsp.brushes.size())) continue;
            const bsp::Brush& brush = bsp.brushes[b];
            bool translucent = false;
            for (int s = 0; s < brush.numSides && !translucent; ++s) {
                const int sideIndex = brush.firstSide + s;
                if (sideIndex < 0 || sideIndex >= int(bsp.brushSides.size())) continue;
                const int shader = bsp.brushSides[sideIndex].shaderNum;
                if (shader < 0 || shader >= int(bsp.shaders.size())) continue;
                translucent = size_t(shader) < translucentShaders.size() ? translucentShaders[shader] != 0
                                                                          : shaderIsTranslucent(bsp.shaders[shader]);
            }
            opaque_[b] = translucent ? 0 : 1;
        }
    }
    if (bsp.visibility.size() >= 8) {
        int32_t header[2];
        std::memcpy(header, bsp.visibility.data(), sizeof(header));
        numClusters_ = header[0];
        bytesPerCluster_ = header[1];
    }
}

static double planeDistance(const bsp::Plane& plane, Vec3 p) {
    return double(plane.normal[0]) * p.x + double(plane.normal[1]) * p.y + double(plane.normal[2]) * p.z -
           double(plane.dist);
}

bool BspTree::segmentCrossesSolid(Vec3 from, Vec3 to) const { return segmentSolidEntry(from, to).has_value(); }

std::optional<Vec3> BspTree::segmentSolidEntry(Vec3 from, Vec3 to) const {
    if (bsp_.nodes.empty()) return std::nullopt;
    constexpr double kOnEpsilon = 0.1;  // TRACE_ON_EPSILON
    struct Local {
        const BspTree& tree;
        std::optional<Vec3> entry(int node, Vec3 start, Vec3 end, int depth) const {
            const bsp::Bsp& bsp = tree.bsp_;
            // Recursion only splits; the near side is walked first, the far side continues the loop.
            while (true) {
                if (node < 0) {
                    const int leaf = -node - 1;
                    const bool solid =
                        leaf < 0 || leaf >= int(bsp.leafs.size()) || bsp.leafs[size_t(leaf)].cluster == -1;
                    return solid ? std::optional<Vec3>(start) : std::nullopt;
                }
                if (node >= int(bsp.nodes.size()) || depth > 4096) return std::nullopt;  // hostile trees
                const bsp::Node& n = bsp.nodes[size_t(node)];
                if (n.planeNum < 0 || n.planeNum >= int(bsp.planes.size())) return std::nullopt;
                const bsp::Plane& plane = bsp.planes[size_t(n.planeNum)];
                const double front = planeDistance(plane, start), back = planeDistance(plane, end);
                if (front >= -kOnEpsilon && back >= -kOnEpsilon) {
                    node = n.children[0];
                } else if (front < kOnEpsilon && back < kOnEpsilon) {
                    node = n.children[1];
                } else {
                    const int side = front < 0 ? 1 : 0;
                    const float frac = float(front / (front - back));
                    const Vec3 mid = start + (end - start) * frac;
                    if (std::optional<Vec3> hit = entry(n.children[side], start, mid, depth + 1)) return hit;
                    node = n.children[1 - side];
                    start = mid;
                }
                ++depth;
            }
        }
    };
    return Local{*this}.entry(0, from, to, 0);
}

int BspTree::leafForPoint(Vec3 point) const {
    if (bsp_.nodes.empty()) return bsp_.leafs.empty() ? -1 : 0;
    // A non-finite point compares as "on the plane" everywhere, which would walk both sides of
    // every node: it lies in no leaf.
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) return -1;
    // Iterative walk; a point on a plane (within 0.1) first tries the front child and keeps its
    // leaf when that leaf belongs to a cluster.
    struct Local {
        const BspTree& tree;
        Vec3 p;
        int walk(int node) const {
            const bsp::Bsp& bsp = tree.bsp_;
            while (node >= 0) {
                const bsp::Node& n = bsp.nodes[node];
                const double d = planeDistance(bsp.planes[n.planeNum], p);
                if (d > 0.1) {
                    node = n.children[0];
                } else if (d < -0.1) {
                    node = n.children[1];
                } else {
                    const int front = walk(n.children[0]);
                    if (front >= 0 && front < int(bsp.leafs.size()) && bsp.leafs[front].cluster != -1) return front;
                    node = n.children[1];
                }
            }
            return -node - 1;
        }
    };
    return Local{*this, point}.walk(0);
}

int BspTree::clusterForPoint(Vec3 point) const {
    const int leaf = leafForPoint(point);
    return leaf < 0 || leaf >= int(bsp_.leafs.size()) ? -1 : bsp_.leafs[leaf].cluster;
}

int BspTree::areaForPoint(Vec3 point) const {
    const int leaf = leafForPoint(point);
    return leaf < 0 || leaf >= int(bsp_.leafs.size()) ? -1 : bsp_.leafs[leaf].area;
}

int BspTree::numClusters() const { return numClusters_; }

bool BspTree::clusterVisible(int from, int to) const {
    if (from < 0 || to < 0) return false;
    if (from == to) return true;
    if (bsp_.visibility.size() <= 8) return true;  // not vised: everything sees everything
    const size_t byte = 8 + size_t(from) * size_t(bytesPerCluster_) + size_t(to >> 3);
    if (from >= numClusters_ || to >= numClusters_ || byte >= bsp_.visibility.size()) return false;
    return (bsp_.visibility[byte] & (1u << (to & 7))) != 0;
}

int BspTree::clusterForPointExt(Vec3 point, float epsilon) const {
    const int leafNum = leafForPoint(point);
    if (leafNum < 0 || leafNum >= int(bsp_.leafs.size())) return -1;
    const bsp::Leaf& leaf = bsp_.leafs[leafNum];
    if (leaf.cluster < 0) return -1;
    for (int i = 0; i < leaf.numLeafBrushes; ++i) {
        const int lb = leaf.firstLeafBrush + i;
        if (lb < 0 || lb >= int(bsp_.leafBrushes.size())) continue;
        const int b = bsp_.leafBrushes[lb];
        if (!brushIsOpaque(b)) continue;
        const bsp::Brush& brush = bsp_.brushes[b];
        bool inside = true;
        for (int s = 0; s < brush.numSides && inside; ++s) {
            const bsp::BrushSide& side = bsp_.brushSides[brush.firstSide + s];
            if (planeDistance(bsp_.planes[side.planeNum], point) > epsilon) inside = false;
        }
        if (inside) return -1 - b;
    }
    return leaf.cluster;
}

std::vector<Vec3> nudgeOffsets(float radius, float step) {
    std::vector<Vec3> offsets;
    if (!(step > 0.0f) || !(radius >= 0.0f)) return {Vec3{}};
    const int n = int(std::floor(radius / step + 1e-4f));
    const float limit = radius * radius * (1.0f + 1e-5f);
    for (int z = -n; z <= n; ++z)
        for (int y = -n; y <= n; ++y)
            for (int x = -n; x <= n; ++x) {
                const Vec3 o{float(x) * step, float(y) * step, float(z) * step};
                if (dot(o, o) <= limit) offsets.push_back(o);
            }
    std::stable_sort(offsets.begin(), offsets.end(), [](Vec3 a, Vec3 b) {
        return std::make_tuple(dot(a, a), a.z, a.y, a.x) < std::make_tuple(dot(b, b), b.z, b.y, b.x);
    });
    return offsets;
}

std::vector<Vec3> nudgeOffsetsInBox(Vec3 halfExtent, int divisions) {
    std::vector<Vec3> offsets;
    const int n = std::max(1, divisions);
    for (int z = -n; z <= n; ++z)
        for (int y = -n; y <= n; ++y)
            for (int x = -n; x <= n; ++x)
                offsets.push_back(Vec3{halfExtent.x * float(x) / float(n), halfExtent.y * float(y) / float(n),
                                       halfExtent.z * float(z) / float(n)});
    // q3map2 widens its random box step by step, each axis in proportion to the cell: the search
    // goes ring by ring in that box metric (largest per-axis fraction of the half extent), then by
    // length within a ring.
    auto ring = [halfExtent](Vec3 o) {
        auto f = [](float v, float h) { return h > 0 ? std::fabs(v) / h : 0.0f; };
        return std::max({f(o.x, halfExtent.x), f(o.y, halfExtent.y), f(o.z, halfExtent.z)});
    };
    std::stable_sort(offsets.begin(), offsets.end(), [&](Vec3 a, Vec3 b) {
        return std::make_tuple(ring(a), dot(a, a), a.z, a.y, a.x) < std::make_tuple(ring(b), dot(b, b), b.z, b.y, b.x);
    });
    return offsets;
}

std::optional<Vec3> BspTree::nudgeOutOfSolid(Vec3 point, float radius, float step, float epsilon) const {
    return nudgeOutOfSolid(point, nudgeOffsets(radius, step), epsilon);
}

std::optional<Vec3> BspTree::nudgeOutOfSolid(Vec3 point, std::span<const Vec3> offsets, float epsilon) const {
    for (const Vec3& offset : offsets) {
        const Vec3 candidate = point + offset;
        if (clusterForPointExt(candidate, epsilon) >= 0) return candidate;
    }
    return std::nullopt;
}

}  // namespace q3::light
