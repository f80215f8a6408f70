// q3map2's trace pieces of the shadow casters (see trace_pieces.h).
#include "trace_pieces.h"

#include <cmath>
#include <utility>

namespace q3::light {
namespace {

constexpr float kClipOnEpsilon = 0.25f;      // TW_ON_EPSILON: corners this close count as on the plane
constexpr int kMaxTraceDepth = 32;           // MAX_TRACE_DEPTH, counted from the head node
constexpr int kMaxLeafTriangles = 5;         // MAX_NODE_TRIANGLES: fewer and a leaf is not split
constexpr float kMinSplitSize = 32.0f;       // MIN_NODE_SIZE: a leaf this thin is not split

struct TraceVert {
    Vec3 xyz;
    float s = 0, t = 0;
};

struct Winding {
    std::vector<TraceVert> v;
    size_t surface = 0;  // index into the input surfaces
};

// q3map2 ClipTraceWinding: the parts of `w` in front of and behind the plane; a winding with no
// corner behind is all front, one with none in front all back. Split points on an axial plane
// take its distance exactly.
void clipWinding(const Winding& w, Vec3 normal, float dist, Winding& front, Winding& back) {
    front.v.clear();
    back.v.clear();
    front.surface = back.surface = w.surface;
    const size_t n = w.v.size();
    std::vector<float> dists(n);
    std::vector<int> sides(n);  // 1 front, -1 back, 0 on
    int counts[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
        dists[i] = dot(normal, w.v[i].xyz) - dist;
        sides[i] = dists[i] < -kClipOnEpsilon ? -1 : dists[i] > kClipOnEpsilon ? 1 : 0;
        ++counts[sides[i] + 1];
    }
    if (counts[0] == 0) {
        front.v = w.v;
        return;
    }
    if (counts[2] == 0) {
        back.v = w.v;
        return;
    }
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        const TraceVert& a = w.v[i];
        const TraceVert& b = w.v[j];
        if (sides[i] == 0) {
            front.v.push_back(a);
            back.v.push_back(a);
            continue;
        }
        (sides[i] > 0 ? front : back).v.push_back(a);
        if (sides[j] == 0 || sides[j] == sides[i]) continue;
        const float frac = dists[i] / (dists[i] - dists[j]);
        TraceVert mid;
        for (int k = 0; k < 3; ++k) {
            if (normal[k] == 1.0f)
                mid.xyz[k] = dist;
            else if (normal[k] == -1.0f)
                mid.xyz[k] = -dist;
            else
                mid.xyz[k] = a.xyz[k] + frac * (b.xyz[k] - a.xyz[k]);
        }
        mid.s = a.s + (b.s - a.s) * frac;
        mid.t = a.t + (b.t - a.t) * frac;
        front.v.push_back(mid);
        back.v.push_back(mid);
    }
}

// The windings that reach each leaf of the BSP tree, with the depth of that leaf (head node 0).
struct Leaf {
    std::vector<Winding> windings;
    int depth = 0;
};

// q3map2 FilterTraceWindingIntoNodes_r: a winding on a node's plane goes to the side it faces,
// uncut; the others are cut by the plane.
void filterIntoLeaves(const bsp::Bsp& bsp, Winding w, Vec3 planeNormal, float planeDist, std::vector<Leaf>& leaves) {
    struct Item {
        Winding w;
        int32_t node;  // >= 0 node, < 0 leaf -(index + 1)
        int depth;
    };
    std::vector<Item> stack;
    stack.push_back({std::move(w), 0, 0});
    while (!stack.empty()) {
        Item item = std::move(stack.back());
        stack.pop_back();
        if (item.node < 0) {
            const size_t leaf = size_t(-(item.node + 1));
            if (leaf < leaves.size()) {
                leaves[leaf].depth = item.depth;
                leaves[leaf].windings.push_back(std::move(item.w));
            }
            continue;
        }
        if (size_t(item.node) >= bsp.nodes.size()) continue;
        const bsp::Node& node = bsp.nodes[size_t(item.node)];
        if (node.planeNum < 0 || size_t(node.planeNum) >= bsp.planes.size()) continue;
        const bsp::Plane& plane = bsp.planes[size_t(node.planeNum)];
        const Vec3 normal = Vec3::fromArray(plane.normal);
        if (dot(normal, planeNormal) > 0.999f && std::fabs(plane.dist - planeDist) < 0.001f) {
            stack.push_back({std::move(item.w), node.children[0], item.depth + 1});
            continue;
        }
        if (dot(normal, -planeNormal) > 0.999f && std::fabs(plane.dist + planeDist) < 0.001f) {
            stack.push_back({std::move(item.w), node.children[1], item.depth + 1});
            continue;
        }
        Winding front, back;
        clipWinding(item.w, normal, plane.dist, front, back);
        if (back.v.size() >= 3) stack.push_back({std::move(back), node.children[1], item.depth + 1});
        if (front.v.size() >= 3) stack.push_back({std::move(front), node.children[0], item.depth + 1});
    }
}

// q3map2 SubdivideTraceNode_r on one leaf: while it holds enough triangles and is wide enough,
// split it at the (floored) mean corner along its longest side; `emit` gets the final windings.
template <typename Emit>
void subdivideLeaf(std::vector<Winding> windings, int depth, Emit&& emit) {
    if (windings.empty()) return;
    if (depth >= kMaxTraceDepth) {
        for (Winding& w : windings) emit(std::move(w));
        return;
    }
    ++depth;
    Bounds bounds;
    double average[3] = {0, 0, 0};
    int count = 0;
    for (const Winding& w : windings)
        for (const TraceVert& v : w.v) {
            bounds.add(v.xyz);
            for (int k = 0; k < 3; ++k) average[k] += double(v.xyz[k]);
            ++count;
        }
    const Vec3 size = bounds.maxs - bounds.mins;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.x && size.y >= size.z ? 1 : 2;
    if (count - int(windings.size()) * 2 < kMaxLeafTriangles || size[axis] <= kMinSplitSize) {
        for (Winding& w : windings) emit(std::move(w));
        return;
    }
    float dist = float(std::floor(average[axis] / count));
    if (dist <= bounds.mins[axis] || dist >= bounds.maxs[axis])
        dist = std::floor(0.5f * (bounds.mins[axis] + bounds.maxs[axis]));
    Vec3 normal;
    normal[axis] = 1.0f;
    std::vector<Winding> fronts, backs;
    for (const Winding& w : windings) {
        Winding front, back;
        clipWinding(w, normal, dist, front, back);
        if (front.v.size() >= 3) fronts.push_back(std::move(front));
        if (back.v.size() >= 3) backs.push_back(std::move(back));
    }
    windings.clear();
    subdivideLeaf(std::move(fronts), depth, emit);
    subdivideLeaf(std::move(backs), depth, emit);
}

// Appends the fan of a winding to `out`, each triangle grown by the barycentric slack unless
// `exact`; triangles whose edge cross product is below the coplanar epsilon are dropped.
void appendPieces(const Winding& w, bool exact, SceneSurface& out) {
    const float e = exact ? 0.0f : kTraceBaryEpsilon;
    const TraceVert& a = w.v[0];
    for (size_t i = 1; i + 1 < w.v.size(); ++i) {
        const TraceVert& b = w.v[i];
        const TraceVert& c = w.v[i + 1];
        const Vec3 e1 = b.xyz - a.xyz, e2 = c.xyz - a.xyz;
        if (length(cross(e1, e2)) < kTraceCoplanarEpsilon) continue;
        // The corners of the region u >= -e, v >= -e, u + v <= 1 + e of the triangle's own
        // barycentric coordinates, the texture coordinates following them.
        const float weights[3][2] = {{-e, -e}, {1 + 2 * e, -e}, {-e, 1 + 2 * e}};
        const uint32_t base = uint32_t(out.xyz.size());
        for (const auto& [u, v] : weights) {
            out.xyz.push_back(a.xyz + e1 * u + e2 * v);
            out.st.push_back(a.s + (b.s - a.s) * u + (c.s - a.s) * v);
            out.st.push_back(a.t + (b.t - a.t) * u + (c.t - a.t) * v);
        }
        for (uint32_t k = 0; k < 3; ++k) out.triangles.push_back(base + k);
    }
}

}  // namespace

std::vector<SceneSurface> traceCasterPieces(const std::vector<SceneSurface>& surfaces, const bsp::Bsp& bsp,
                                            const TraceSceneOptions& options) {
    std::vector<SceneSurface> out(surfaces.size());
    std::vector<Winding> direct;  // without a tree: the triangles themselves
    std::vector<Leaf> leaves(bsp.nodes.empty() ? 0 : bsp.leafs.size());
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const SceneSurface& s = surfaces[i];
        if (!TraceScene::castsShadow(s, options)) {
            out[i] = s;
            continue;
        }
        SceneSurface& piece = out[i];
        piece.surfaceNum = s.surfaceNum;
        piece.shader = s.shader;
        piece.castShadows = s.castShadows;
        piece.skyIndex = s.skyIndex;
        piece.isPatch = s.isPatch;
        for (size_t t = 0; t + 2 < s.triangles.size(); t += 3) {
            Winding w;
            w.surface = i;
            for (int k = 0; k < 3; ++k) {
                const uint32_t idx = s.triangles[t + size_t(k)];
                if (idx >= s.xyz.size()) break;
                TraceVert v;
                v.xyz = s.xyz[idx];
                if (size_t(idx) * 2 + 1 < s.st.size()) {
                    v.s = s.st[size_t(idx) * 2];
                    v.t = s.st[size_t(idx) * 2 + 1];
                }
                w.v.push_back(v);
            }
            if (w.v.size() != 3) continue;
            // q3map2 drops a triangle whose corners give no plane (PlaneFromPoints).
            const Vec3 n = cross(w.v[2].xyz - w.v[0].xyz, w.v[1].xyz - w.v[0].xyz);
            const float len = length(n);
            if (!(len > 0)) continue;
            const Vec3 normal = n / len;
            const float dist = dot(w.v[0].xyz, normal);
            if (leaves.empty())
                direct.push_back(std::move(w));
            else
                filterIntoLeaves(bsp, std::move(w), normal, dist, leaves);
        }
    }
    auto emit = [&](Winding&& w) {
        const SceneSurface& s = surfaces[w.surface];
        const bool exact = s.shader && (s.shader->alphaShadow || s.shader->lightFilter) && !s.shader->sky;
        appendPieces(w, exact, out[w.surface]);
    };
    for (Winding& w : direct) emit(std::move(w));
    for (Leaf& leaf : leaves) subdivideLeaf(std::move(leaf.windings), leaf.depth, emit);
    return out;
}

}  // namespace q3::light
