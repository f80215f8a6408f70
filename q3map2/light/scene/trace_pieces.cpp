// q3map2's trace pieces of the shadow casters (see trace_pieces.h).
#include "trace_pieces.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <array>
#include <cmath>
#include <span>
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

// A winding's corners: a few on the spot (a triangle gains one corner per cut, so nearly every
// piece fits), more on the heap. Clipping runs for every cut of every caster, and heap corners
// made the allocator its largest cost.
class Corners {
public:
    size_t size() const { return size_; }
    void clear() {
        size_ = 0;
        heap_.clear();
    }
    void push_back(const TraceVert& v) {
        if (size_ < kInline) {
            inline_[size_++] = v;
            return;
        }
        if (size_ == kInline) heap_.assign(inline_.begin(), inline_.end());
        heap_.push_back(v);
        ++size_;
    }
    const TraceVert* begin() const { return size_ <= kInline ? inline_.data() : heap_.data(); }
    const TraceVert* end() const { return begin() + size_; }
    const TraceVert& operator[](size_t i) const { return begin()[i]; }

private:
    static constexpr size_t kInline = 12;
    std::array<TraceVert, kInline> inline_;
    size_t size_ = 0;
    std::vector<TraceVert> heap_;  // every corner, once there are more than kInline
};

struct Winding {
    Corners v;
    size_t surface = 0;  // index into the input surfaces
};

// q3map2 ClipTraceWinding: a winding with no corner behind the plane is all front (returns 0),
// one with none in front all back (1), and `front` and `back` are then left empty: the caller
// keeps the winding whole. Otherwise (-1) they receive the parts. Split points on an axial plane
// take its distance exactly.
int clipWinding(const Winding& w, Vec3 normal, float dist, Winding& front, Winding& back) {
    front.v.clear();
    back.v.clear();
    front.surface = back.surface = w.surface;
    const size_t n = w.v.size();
    // Scratch on the stack for the usual few corners: this runs for every cut of every caster.
    constexpr size_t kOnStack = 32;
    float distsOnStack[kOnStack];
    int sidesOnStack[kOnStack];
    std::vector<float> distsOnHeap;
    std::vector<int> sidesOnHeap;
    float* dists = distsOnStack;
    int* sides = sidesOnStack;  // 1 front, -1 back, 0 on
    if (n > kOnStack) {
        distsOnHeap.resize(n);
        sidesOnHeap.resize(n);
        dists = distsOnHeap.data();
        sides = sidesOnHeap.data();
    }
    int counts[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
        dists[i] = dot(normal, w.v[i].xyz) - dist;
        sides[i] = dists[i] < -kClipOnEpsilon ? -1 : dists[i] > kClipOnEpsilon ? 1 : 0;
        ++counts[sides[i] + 1];
    }
    if (counts[0] == 0) return 0;
    if (counts[2] == 0) return 1;
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
    return -1;
}

// The windings that reach each leaf of the BSP tree, with the depth of that leaf (head node 0).
struct Leaf {
    std::vector<Winding> windings;
    int depth = 0;
};

// A winding that reached a leaf at a depth (filterIntoLeaves' output, in the order it reached them).
struct LeafWinding {
    size_t leaf;
    int depth;
    Winding w;
};

// q3map2 FilterTraceWindingIntoNodes_r: a winding on a node's plane goes to the side it faces,
// uncut; the others are cut by the plane. A winding that lies on one side walks on without a copy;
// of a cut one, the front part is walked first.
void filterIntoLeaves(const bsp::Bsp& bsp, Winding w, Vec3 planeNormal, float planeDist, size_t leafCount,
                      std::vector<LeafWinding>& out) {
    struct Item {
        Winding w;
        int32_t node;  // >= 0 node, < 0 leaf -(index + 1)
        int depth;
    };
    std::vector<Item> pending;
    Winding current = std::move(w), front, back;
    int32_t node = 0;
    int depth = 0;
    auto takePending = [&] {
        if (pending.empty()) return false;
        current = std::move(pending.back().w);
        node = pending.back().node;
        depth = pending.back().depth;
        pending.pop_back();
        return true;
    };
    while (true) {
        const bool valid = node >= 0 && size_t(node) < bsp.nodes.size() && bsp.nodes[size_t(node)].planeNum >= 0 &&
                           size_t(bsp.nodes[size_t(node)].planeNum) < bsp.planes.size();
        if (!valid) {
            if (node < 0 && size_t(-(node + 1)) < leafCount) out.push_back({size_t(-(node + 1)), depth, std::move(current)});
            if (!takePending()) return;
            continue;
        }
        const bsp::Node& n = bsp.nodes[size_t(node)];
        const bsp::Plane& plane = bsp.planes[size_t(n.planeNum)];
        const Vec3 normal = Vec3::fromArray(plane.normal);
        ++depth;
        if (dot(normal, planeNormal) > 0.999f && std::fabs(plane.dist - planeDist) < 0.001f) {
            node = n.children[0];
            continue;
        }
        if (dot(normal, -planeNormal) > 0.999f && std::fabs(plane.dist + planeDist) < 0.001f) {
            node = n.children[1];
            continue;
        }
        const int side = clipWinding(current, normal, plane.dist, front, back);
        if (side >= 0) {
            node = n.children[side];
            continue;
        }
        if (back.v.size() >= 3) pending.push_back({std::move(back), n.children[1], depth});
        if (front.v.size() >= 3) {
            current = std::move(front);
            node = n.children[0];
        } else if (!takePending()) {
            return;
        }
    }
}

// Where q3map2's SubdivideTraceNode_r splits a leaf holding `windings` at `depth`: along its
// longest side at the (floored) mean corner, when it holds enough triangles and is wide enough.
struct LeafSplit {
    bool split = false;
    int axis = 0;
    float dist = 0;
};

LeafSplit leafSplit(const std::vector<Winding>& windings, int depth) {
    LeafSplit s;
    if (windings.empty() || depth >= kMaxTraceDepth) return s;
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
    s.axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.x && size.y >= size.z ? 1 : 2;
    if (count - int(windings.size()) * 2 < kMaxLeafTriangles || size[s.axis] <= kMinSplitSize) return s;
    s.split = true;
    s.dist = float(std::floor(average[s.axis] / count));
    if (s.dist <= bounds.mins[s.axis] || s.dist >= bounds.maxs[s.axis])
        s.dist = std::floor(0.5f * (bounds.mins[s.axis] + bounds.maxs[s.axis]));
    return s;
}

// q3map2 SubdivideTraceNode_r on one leaf: split while leafSplit says so; `emit` gets the final
// windings.
template <typename Emit>
void subdivideLeaf(std::vector<Winding> windings, int depth, Emit&& emit) {
    const LeafSplit split = leafSplit(windings, depth);
    if (!split.split) {
        for (Winding& w : windings) emit(std::move(w));
        return;
    }
    Vec3 normal;
    normal[split.axis] = 1.0f;
    std::vector<Winding> fronts, backs;
    fronts.reserve(windings.size());  // a winding's parts grow each half by one at most
    backs.reserve(windings.size());
    Winding front, back;
    for (Winding& w : windings) {
        const int side = clipWinding(w, normal, split.dist, front, back);
        if (side >= 0) {
            (side == 0 ? fronts : backs).push_back(std::move(w));
            continue;
        }
        if (front.v.size() >= 3) fronts.push_back(std::move(front));
        if (back.v.size() >= 3) backs.push_back(std::move(back));
    }
    std::vector<Winding>().swap(windings);  // freed before the halves are split further
    subdivideLeaf(std::move(fronts), depth + 1, emit);
    subdivideLeaf(std::move(backs), depth + 1, emit);
}

// The corners of a winding where it came to rest.
struct CornerSpan {
    const TraceVert* first;
    size_t count;
};

// The windings a leaf's subdivision emits, in order, their corners side by side: a few bytes a
// corner instead of a whole winding with room for twelve.
struct EmittedPieces {
    struct Entry {
        size_t surface;
        size_t first, count;  // in `corners`
    };
    std::vector<TraceVert> corners;
    std::vector<Entry> windings;

    void add(const Winding& w) {
        windings.push_back({w.surface, corners.size(), w.v.size()});
        corners.insert(corners.end(), w.v.begin(), w.v.end());
    }
};

// Appends the fan of a winding to `out`, each triangle grown by the barycentric slack unless
// `exact`; triangles whose edge cross product is below the coplanar epsilon are dropped. Only the
// exact pieces (filtering surfaces, whose texture a ray reads) keep texture coordinates.
void appendPieces(CornerSpan w, bool exact, SceneSurface& out) {
    const float e = exact ? 0.0f : kTraceBaryEpsilon;
    const TraceVert& a = w.first[0];
    for (size_t i = 1; i + 1 < w.count; ++i) {
        const TraceVert& b = w.first[i];
        const TraceVert& c = w.first[i + 1];
        const Vec3 e1 = b.xyz - a.xyz, e2 = c.xyz - a.xyz;
        if (length(cross(e1, e2)) < kTraceCoplanarEpsilon) continue;
        // The corners of the region u >= -e, v >= -e, u + v <= 1 + e of the triangle's own
        // barycentric coordinates, the texture coordinates following them.
        const float weights[3][2] = {{-e, -e}, {1 + 2 * e, -e}, {-e, 1 + 2 * e}};
        const uint32_t base = uint32_t(out.xyz.size());
        for (const auto& [u, v] : weights) {
            out.xyz.push_back(a.xyz + e1 * u + e2 * v);
            if (!exact) continue;
            out.st.push_back(a.s + (b.s - a.s) * u + (c.s - a.s) * v);
            out.st.push_back(a.t + (b.t - a.t) * u + (c.t - a.t) * v);
        }
        for (uint32_t k = 0; k < 3; ++k) out.triangles.push_back(base + k);
    }
}

// A surface's identity and shadow settings without its geometry, which its pieces then fill.
SceneSurface withoutGeometry(const SceneSurface& s) {
    SceneSurface out;
    out.surfaceNum = s.surfaceNum;
    out.shader = s.shader;
    out.castShadows = s.castShadows;
    out.skyIndex = s.skyIndex;
    out.isPatch = s.isPatch;
    return out;
}

// A caster that stops every ray meeting it: not sky (sun rays end there), not a filter.
bool opaqueCaster(const SceneSurface& s) {
    return !s.shader || (!s.shader->sky && !s.shader->alphaShadow && !s.shader->lightFilter);
}

}  // namespace

CasterPieces traceCasterPieces(const std::vector<SceneSurface>& surfaces, const bsp::Bsp& bsp,
                               const TraceSceneOptions& options, TraceLeafContents* contents, int threads) {
    CasterPieces result;
    std::vector<SceneSurface>& out = result.surfaces;
    out.resize(surfaces.size());
    const size_t leafCount = bsp.nodes.empty() ? 0 : bsp.leafs.size();
    // Every caster's triangles filtered down the tree, each surface on its own (in parallel); the
    // results are gathered in surface order below, so the leaves hold what the sequential filter
    // would put there, in the same order.
    std::vector<std::vector<LeafWinding>> filtered(surfaces.size());
    std::vector<std::vector<Winding>> direct(surfaces.size());  // without a tree: the triangles themselves
    std::vector<Leaf> leaves(leafCount);
    // Per leaf: whether it holds pieces, whether q3map2 subdivides it, and the windings its
    // subdivision emits, in order.
    std::vector<uint8_t> holdsPieces(leafCount, 0), subdivided(leafCount, 0);
    std::vector<EmittedPieces> emitted(leafCount), emittedForSun(leafCount);
    auto filterSurface = [&](size_t i) {
        const SceneSurface& s = surfaces[i];
        if (!TraceScene::castsShadow(s, options)) {
            out[i] = s;
            return;
        }
        out[i] = withoutGeometry(s);
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
            if (leafCount == 0)
                direct[i].push_back(std::move(w));
            else
                filterIntoLeaves(bsp, std::move(w), normal, dist, leafCount, filtered[i]);
        }
    };
    // An opaque piece in a leaf outside every cluster matters only to rays that pass through that
    // leaf, as q3map2 tests a leaf's triangles only for the rays it walks through: left among the
    // others, it also stopped rays that graze the leaf. Point-light rays stop at any such leaf
    // (bsp_tree.h), so they never need it; sun rays stop there too unless the tracer split the
    // leaf (sky_ray_solid.h), and only those pieces are kept, for sun rays alone.
    auto subdivide = [&](size_t l) {
        const bool split = leafSplit(leaves[l].windings, leaves[l].depth).split;
        if (contents) {
            holdsPieces[l] = leaves[l].windings.empty() ? 0 : 1;
            subdivided[l] = split ? 1 : 0;
        }
        const bool outside = bsp.leafs[l].cluster == -1;
        subdivideLeaf(std::move(leaves[l].windings), leaves[l].depth, [&](Winding&& w) {
            if (!outside || !opaqueCaster(surfaces[w.surface]))
                emitted[l].add(w);
            else if (split && options.sunRays)
                emittedForSun[l].add(w);
        });
    };
    tbb::task_arena(threads > 0 ? threads : tbb::task_arena::automatic).execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, surfaces.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) filterSurface(i);
        });
        for (std::vector<LeafWinding>& list : filtered) {
            for (LeafWinding& lw : list) {
                leaves[lw.leaf].depth = lw.depth;
                leaves[lw.leaf].windings.push_back(std::move(lw.w));
            }
            std::vector<LeafWinding>().swap(list);
        }
        tbb::parallel_for(tbb::blocked_range<size_t>(0, leafCount, 16), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t l = r.begin(); l != r.end(); ++l) subdivide(l);
        });
    });
    // Each surface's pieces in the order the sequential emission gives (direct windings exist only
    // without a tree, emitted ones only with one), fanned out surface by surface in parallel.
    std::vector<std::vector<CornerSpan>> bySurface(surfaces.size()), forSunBySurface(surfaces.size());
    for (const std::vector<Winding>& list : direct)
        for (const Winding& w : list) bySurface[w.surface].push_back({w.v.begin(), w.v.size()});
    auto gather = [](const std::vector<EmittedPieces>& leaves, std::vector<std::vector<CornerSpan>>& to) {
        for (const EmittedPieces& leaf : leaves)
            for (const EmittedPieces::Entry& w : leaf.windings)
                to[w.surface].push_back({leaf.corners.data() + w.first, w.count});
    };
    gather(emitted, bySurface);
    gather(emittedForSun, forSunBySurface);
    bool anyForSun = false;
    for (const std::vector<CornerSpan>& list : forSunBySurface) anyForSun = anyForSun || !list.empty();
    if (anyForSun) result.forSunOnly.resize(surfaces.size());
    auto fanInto = [&](const SceneSurface& s, std::span<const CornerSpan> windings, SceneSurface& to) {
        const bool exact = s.shader && (s.shader->alphaShadow || s.shader->lightFilter) && !s.shader->sky;
        size_t fans = 0;  // an upper bound of the triangles, so that the arrays grow once
        for (const CornerSpan& w : windings) fans += w.count >= 3 ? w.count - 2 : 0;
        to.xyz.reserve(fans * 3);
        if (exact) to.st.reserve(fans * 6);
        to.triangles.reserve(fans * 3);
        for (const CornerSpan& w : windings) appendPieces(w, exact, to);
    };
    auto fan = [&](size_t i) {
        fanInto(surfaces[i], bySurface[i], out[i]);
        if (forSunBySurface[i].empty()) return;
        result.forSunOnly[i] = withoutGeometry(surfaces[i]);
        fanInto(surfaces[i], forSunBySurface[i], result.forSunOnly[i]);
    };
    tbb::task_arena(threads > 0 ? threads : tbb::task_arena::automatic).execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, surfaces.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) fan(i);
        });
    });
    if (contents) {
        contents->holdsPieces = std::move(holdsPieces);
        contents->subdivided = std::move(subdivided);
    }
    return result;
}

}  // namespace q3::light
