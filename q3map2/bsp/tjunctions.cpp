#include "tjunctions.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <list>
#include <unordered_map>
#include <string>

#include "log.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

constexpr float kLinePositionEpsilon = 0.25f;
constexpr double kPointOnLineEpsilon = 0.25;  // compared in double, as q3map2's float_equal_epsilon
constexpr float kDegenerateEpsilon = 0.1f;
constexpr double kInsertEpsilon = 0.1;  // ON_EPSILON, a double: `start + ON_EPSILON` is not rounded to float
constexpr int kMaxSurfaceVerts = 256;

struct EdgePoint {
    float intercept;
    Vec3 xyz;
};

struct EdgeLine {
    Vec3 normal1, normal2;  // two planes whose intersection is the line
    float dist1 = 0, dist2 = 0;
    Vec3 origin, dir;
    std::list<EdgePoint> points;  // by intercept along dir
};

struct PendingEdge {  // a non-axial edge, registered after all axial ones
    float length;
    Vec3 v1, v2;
    size_t surface;
    int vert;  // the face vertex starting the edge; -1 for a patch border
};

// q3map2's VectorNormalize: divides in double, so that an axial difference gives exactly +-1 (a
// float reciprocal gives 0.99999994 for 41, which the axial test rejects); returns the length.
float normalizeExact(Vec3& v) {
    const double x = v.x, y = v.y, z = v.z;
    const double len = std::sqrt(x * x + y * y + z * z);
    if (len == 0) {
        v = {};
        return 0;
    }
    v = {float(x / len), float(y / len), float(z / len)};
    return float(len);
}

// Two unit vectors perpendicular to `forward` and to each other (2.5.17n MakeNormalVectors: the
// axis of forward's smallest component crossed with it, then their cross). For a horizontal line
// the planes are the vertical one through it and the horizontal one, so a point 0.286 beside it
// is off the line, where the older rotate-and-negate planes (tilted) let it through.
void normalVectors(const Vec3& forward, Vec3& right, Vec3& up) {
    int smallest = 0;
    for (int k = 1; k < 3; ++k)
        if (std::fabs(forward[k]) < std::fabs(forward[smallest])) smallest = k;
    Vec3 axis;
    axis[smallest] = 1;
    right = cross(axis, forward);
    normalizeExact(right);
    up = cross(right, forward);
}

// Strictly within, as q3map2's float_equal_epsilon: a point exactly 0.25 off a line is not on it.
bool nearlyEqual(float a, float b, float epsilon) { return std::fabs(b - a) < epsilon; }
bool nearlyEqual(double a, double b, double epsilon) { return std::fabs(b - a) < epsilon; }

// The edge lines, with an index that finds the first line (in creation order) holding both ends of
// an edge without testing every line: lines along a world axis are filed under the unit cell of
// their other two coordinates (an edge's end within 0.25 of such a line lies in one of at most four
// cells around it); the few other lines are tested one by one.
class EdgeLines {
public:
    std::vector<EdgeLine> lines;

    // The line of the edge v1-v2 (created when no line holds both ends); -1 for a degenerate edge.
    int add(const Vec3& v1, const Vec3& v2, TJunctionCounts& counts) {
        Vec3 dir = v2 - v1;
        if (normalizeExact(dir) < 0.1f) {
            ++counts.degenerateEdges;
            return -1;
        }
        // Faces sharing an edge register it twice: its line is the one found the first time (lines
        // never change and later ones come after it), and its ends are on that line already.
        const EdgeKey key = edgeKey(v1, v2);
        if (auto known = known_.find(key); known != known_.end() && holds(lines[size_t(known->second)], v1, v2))
            return known->second;
        const int found = firstHolding(v1, v2);
        if (found >= 0) {
            insert(v1, lines[size_t(found)]);
            insert(v2, lines[size_t(found)]);
            known_.insert_or_assign(key, found);
            return found;
        }
        known_.insert_or_assign(key, int(lines.size()));
        EdgeLine& e = lines.emplace_back();
        e.origin = v1;
        e.dir = dir;
        normalVectors(e.dir, e.normal1, e.normal2);
        e.dist1 = dot(e.origin, e.normal1);
        e.dist2 = dot(e.origin, e.normal2);
        insert(v1, e);
        insert(v2, e);
        const int index = int(lines.size()) - 1;
        const int axis = alongAxis(dir);
        if (axis < 0) {
            general_.push_back(index);
            planeX_.push_back(e.normal1.x);
            planeY_.push_back(e.normal1.y);
            planeZ_.push_back(e.normal1.z);
            planeDist_.push_back(e.dist1);
        } else {
            const auto [a, b] = otherAxes(axis);
            cells_[cellKey(axis, cellOf(v1[a]), cellOf(v1[b]))].push_back(index);
        }
        return index;
    }

private:
    using CellKey = uint64_t;
    using EdgeKey = std::array<uint32_t, 6>;

    // The two ends' bit patterns, lower end first, so that both directions of an edge meet.
    static EdgeKey edgeKey(const Vec3& v1, const Vec3& v2) {
        std::array<uint32_t, 3> a, b;
        for (int k = 0; k < 3; ++k) {
            a[size_t(k)] = std::bit_cast<uint32_t>(v1[k]);
            b[size_t(k)] = std::bit_cast<uint32_t>(v2[k]);
        }
        if (b < a) std::swap(a, b);
        return {a[0], a[1], a[2], b[0], b[1], b[2]};
    }
    struct EdgeKeyHash {
        size_t operator()(const EdgeKey& k) const {
            uint64_t h = 0xcbf29ce484222325ull;
            for (uint32_t v : k) h = (h ^ v) * 0x100000001b3ull;
            return size_t(h);
        }
    };

    static int alongAxis(const Vec3& dir) {
        for (int k = 0; k < 3; ++k)
            if (dir[(k + 1) % 3] == 0 && dir[(k + 2) % 3] == 0) return k;
        return -1;
    }
    static std::pair<int, int> otherAxes(int axis) { return {(axis + 1) % 3, (axis + 2) % 3}; }
    static int64_t cellOf(float v) { return int64_t(std::floor(v)); }
    static CellKey cellKey(int axis, int64_t a, int64_t b) {
        return (CellKey(axis) << 62) ^ (CellKey(uint32_t(int32_t(a))) << 31) ^ CellKey(uint32_t(int32_t(b)));
    }

    bool holds(const EdgeLine& e, const Vec3& v1, const Vec3& v2) const {
        // Float dot products, their difference from the float distance taken in double.
        auto on = [](const Vec3& v, const Vec3& n, float d) {
            return nearlyEqual(double(dot(v, n)), double(d), kPointOnLineEpsilon);
        };
        return on(v1, e.normal1, e.dist1) && on(v1, e.normal2, e.dist2) && on(v2, e.normal1, e.dist1) &&
               on(v2, e.normal2, e.dist2);
    }

    // The smallest index of a line holding both ends, or -1.
    int firstHolding(const Vec3& v1, const Vec3& v2) const {
        int best = std::numeric_limits<int>::max();
        // Most lines miss the first end on their first plane. That test runs on blocks of lines
        // without branches (so that it vectorises), a little wider than the exact one, which
        // decides for the lines it lets through.
        const size_t count = general_.size();
        for (size_t block = 0; block < count && best == std::numeric_limits<int>::max(); block += kPlaneBlock) {
            const size_t end = std::min(count, block + kPlaneBlock);
            std::array<bool, kPlaneBlock> near{};
            for (size_t i = block; i < end; ++i)
                near[i - block] = std::fabs(v1.x * planeX_[i] + v1.y * planeY_[i] + v1.z * planeZ_[i] - planeDist_[i]) <
                                  float(kPointOnLineEpsilon) + kPlaneFilterSlack;
            for (size_t word = 0; word < kPlaneBlock && best == std::numeric_limits<int>::max(); word += 8) {
                uint64_t any = 0;
                std::memcpy(&any, near.data() + word, sizeof any);
                if (!any) continue;  // eight lines missed at once
                for (size_t i = block + word; i < std::min(end, block + word + 8); ++i) {
                    if (!near[i - block] || !holds(lines[size_t(general_[i])], v1, v2)) continue;
                    best = general_[i];
                    break;
                }
            }
        }
        for (int axis = 0; axis < 3; ++axis) {
            const auto [a, b] = otherAxes(axis);
            for (int64_t ca = cellOf(v1[a] - 0.5f); ca <= cellOf(v1[a] + 0.5f); ++ca)
                for (int64_t cb = cellOf(v1[b] - 0.5f); cb <= cellOf(v1[b] + 0.5f); ++cb) {
                    auto it = cells_.find(cellKey(axis, ca, cb));
                    if (it == cells_.end()) continue;
                    for (int index : it->second) {
                        if (index >= best) break;
                        if (holds(lines[size_t(index)], v1, v2)) best = index;
                    }
                }
        }
        return best == std::numeric_limits<int>::max() ? -1 : best;
    }

    static void insert(const Vec3& v, EdgeLine& e) {
        const EdgePoint p{dot(v - e.origin, e.dir), v};
        for (auto it = e.points.begin(); it != e.points.end(); ++it) {
            if (nearlyEqual(p.intercept, it->intercept, kLinePositionEpsilon)) return;  // already there
            if (p.intercept < it->intercept) {
                e.points.insert(it, p);
                return;
            }
        }
        e.points.push_back(p);
    }

    std::vector<int> general_;  // lines not along an axis, in creation order
    // Their first plane (normal1, dist1), one array per component.
    std::vector<float> planeX_, planeY_, planeZ_, planeDist_;
    static constexpr size_t kPlaneBlock = 64;
    static constexpr float kPlaneFilterSlack = 0.01f;
    std::unordered_map<CellKey, std::vector<int>> cells_;
    std::unordered_map<EdgeKey, int, EdgeKeyHash> known_;  // the line of every edge registered
};

bool isAxial(const Vec3& dir) { return std::fabs(dir.x + dir.y + dir.z) == 1.0f; }

// A patch border span whose middle control point lies on the line of its ends (within 0.1).
bool collinear(const Vec3& v1, const Vec3& v2, const Vec3& v3) {
    const Vec3 mid = v2 - v1;
    Vec3 dir = v3 - v1;
    if (normalizeExact(dir) == 0) return false;
    return length(mid - dir * dot(mid, dir)) < 0.1f;
}

bool skipped(const DrawSurface& ds) {
    const ShaderInfo& si = *ds.shader;
    return si.isNoDraw() || si.autosprite || si.noTJunc || ds.verts.empty();
}

// The edge line each face vertex's edge (to the next vertex) lies on.
using EdgeIndexes = std::vector<std::vector<int>>;

void registerEdges(std::vector<DrawSurface>& surfaces, EdgeLines& lines, EdgeIndexes& edgeOf,
                   std::vector<PendingEdge>& pending, TJunctionCounts& counts) {
    auto addEdge = [&](const Vec3& v1, const Vec3& v2, size_t surface, int vert) {
        Vec3 dir = v2 - v1;
        const float d = normalizeExact(dir);
        if (d < 0.1f) {
            ++counts.degenerateEdges;
            return -1;
        }
        if (!isAxial(dir)) {
            pending.push_back({d, v1, v2, surface, vert});
            return -1;
        }
        return lines.add(v1, v2, counts);
    };
    for (size_t s = 0; s < surfaces.size(); ++s) {
        DrawSurface& ds = surfaces[s];
        if (skipped(ds)) continue;
        if (ds.kind == SurfaceKind::Face) {
            const int n = int(ds.verts.size());
            edgeOf[s].assign(size_t(n), -1);
            // The closing edge (last vertex to first) comes first, as 2.5.17n's AddSurfaceEdges walks
            // (prev, next) pairs from (end - 1, begin): which edge of a face creates a line decides
            // which later edges join it (oacmpdm5: 1268 axial lines in vertex order, 1290 so).
            for (int k = 0; k < n; ++k) {
                const int i = (k + n - 1) % n;
                edgeOf[s][size_t(i)] = addEdge(xyzOf(ds.verts[size_t(i)]), xyzOf(ds.verts[size_t((i + 1) % n)]), s, i);
            }
        } else if (ds.kind == SurfaceKind::Patch) {
            // Straight border spans of a patch, so that faces meeting a patch get its vertices.
            auto at = [&](int x, int y) { return xyzOf(ds.verts[size_t(y * ds.patchWidth + x)]); };
            auto span = [&](Vec3 a, Vec3 b, Vec3 c) {
                if (collinear(a, b, c)) addEdge(a, c, s, -1);
            };
            for (int i = 0; i < ds.patchWidth - 2; i += 2) {
                span(at(i, 0), at(i + 1, 0), at(i + 2, 0));
                span(at(i, ds.patchHeight - 1), at(i + 1, ds.patchHeight - 1), at(i + 2, ds.patchHeight - 1));
            }
            for (int i = 0; i < ds.patchHeight - 2; i += 2) {
                span(at(0, i), at(0, i + 1), at(0, i + 2));
                span(at(ds.patchWidth - 1, i), at(ds.patchWidth - 1, i + 1), at(ds.patchWidth - 1, i + 2));
            }
        }
    }
}

// Inserts the edge lines' points into one face and rotates it to start between unsplit edges.
void fixFace(DrawSurface& ds, const std::vector<int>& edgeOf, const EdgeLines& lines, TJunctionCounts& counts) {
    const int n = int(ds.verts.size());
    std::vector<bsp::DrawVert> verts;
    std::vector<bool> added;
    std::vector<int> originals;
    for (int i = 0; i < n; ++i) {
        verts.push_back(ds.verts[size_t(i)]);
        added.push_back(!ds.tjunctionVerts.empty() && ds.tjunctionVerts[size_t(i)]);
        originals.push_back(i);
        const int line = edgeOf[size_t(i)];
        if (line < 0) continue;
        const bsp::DrawVert& v1 = ds.verts[size_t(i)];
        const bsp::DrawVert& v2 = ds.verts[size_t((i + 1) % n)];
        const EdgeLine& e = lines.lines[size_t(line)];
        const float start = dot(xyzOf(v1) - e.origin, e.dir);
        const float end = dot(xyzOf(v2) - e.origin, e.dir);
        auto insert = [&](const EdgePoint& p) {
            if (int(verts.size()) >= kMaxSurfaceVerts)
                throw CompileError("face of shader " + ds.shader->name + " needs more than " +
                                   std::to_string(kMaxSurfaceVerts) + " vertices after T-junction fixing");
            bsp::DrawVert v{};
            p.xyz.toArray(v.xyz);
            const float frac = (p.intercept - start) / (end - start);
            for (int k = 0; k < 2; ++k) v.st[k] = v1.st[k] + (v2.st[k] - v1.st[k]) * frac;
            std::copy(v1.normal, v1.normal + 3, v.normal);
            for (int k = 0; k < 4; ++k)
                v.color[k] = uint8_t(std::clamp(float(v1.color[k]) + frac * float(int(v2.color[k]) - int(v1.color[k])), 0.0f, 255.0f));
            for (int k = 0; k < 2; ++k) v.lightmap[k] = (v1.lightmap[k] + v2.lightmap[k]) * 0.5f;
            verts.push_back(v);
            added.push_back(true);
            originals.push_back(i);
        };
        if (start < end) {
            for (const EdgePoint& p : e.points) {
                if (p.intercept <= start + kInsertEpsilon) continue;
                if (p.intercept > end - kInsertEpsilon) break;
                insert(p);
            }
        } else {
            for (auto it = e.points.rbegin(); it != e.points.rend(); ++it) {
                if (it->intercept >= start - kInsertEpsilon) continue;
                if (it->intercept < end + kInsertEpsilon) break;
                insert(*it);
            }
        }
    }
    const int count = int(verts.size());
    counts.addedVerts += count - n;
    counts.totalVerts += count;
    int first = 0;
    for (; first < count; ++first) {
        if (originals[size_t((first + 1) % count)] == originals[size_t(first)]) continue;
        if (originals[size_t((first + count - 1) % count)] == originals[size_t((first + count - 2) % count)]) continue;
        break;
    }
    if (first == 0) ++counts.natural;
    else if (first == count) ++counts.cantOrder;
    else ++counts.rotated;
    // q3map2 2.5.17n moves the start of every face it does not keep in order (rotated or not
    // orderable) by one vertex, whichever vertex its search found: it writes verts + 1 .. end, then
    // verts[0].
    if (first != 0) first = 1;
    ds.verts.clear();
    ds.tjunctionVerts.clear();
    for (int j = 0; j < count; ++j) {
        ds.verts.push_back(verts[size_t((j + first) % count)]);
        ds.tjunctionVerts.push_back(added[size_t((j + first) % count)]);
    }
}

// Nearest integer coordinate when either end is within 0.01 of one, else the first end's.
float weldComponent(float a, float b) {
    const float ai = std::rint(a), bi = std::rint(b);
    const float ad = std::fabs(ai - a), bd = std::fabs(bi - b);
    if (ad < bd) return ad < 0.01f ? ai : a;
    return bd < 0.01f ? bi : b;
}

// Welds vertices closer than 0.1; false when fewer than three remain.
bool fixBrokenFace(DrawSurface& ds) {
    for (int i = 0; i < int(ds.verts.size()); ++i) {
        const int n = int(ds.verts.size());
        bsp::DrawVert& dv1 = ds.verts[size_t(i)];
        const bsp::DrawVert& dv2 = ds.verts[size_t((i + 1) % n)];
        if (length(xyzOf(dv1) - xyzOf(dv2)) >= kDegenerateEpsilon) continue;
        bsp::DrawVert avg{};
        for (int k = 0; k < 3; ++k) avg.xyz[k] = weldComponent(dv1.xyz[k], dv2.xyz[k]);
        Vec3 normal = Vec3::fromArray(dv1.normal) + Vec3::fromArray(dv2.normal);
        normalizeExact(normal);
        normal.toArray(avg.normal);
        for (int k = 0; k < 2; ++k) {
            avg.st[k] = (dv1.st[k] + dv2.st[k]) * 0.5f;
            avg.lightmap[k] = (dv1.lightmap[k] + dv2.lightmap[k]) * 0.5f;
        }
        for (int k = 0; k < 4; ++k) avg.color[k] = uint8_t((int(dv1.color[k]) + int(dv2.color[k])) >> 1);
        const bool junction = !ds.tjunctionVerts.empty() && ds.tjunctionVerts[size_t(i)] &&
                              ds.tjunctionVerts[size_t((i + 1) % n)];
        dv1 = avg;
        const size_t erase = size_t((i + 1) % n);  // the next vertex goes
        ds.verts.erase(ds.verts.begin() + std::ptrdiff_t(erase));
        if (!ds.tjunctionVerts.empty()) {
            ds.tjunctionVerts[size_t(i)] = junction;
            ds.tjunctionVerts.erase(ds.tjunctionVerts.begin() + std::ptrdiff_t(erase));
        }
        --i;  // the welded vertex has a new neighbour
    }
    return ds.verts.size() >= 3;
}

}  // namespace

TJunctionCounts fixTJunctions(std::vector<DrawSurface>& surfaces) {
    TJunctionCounts counts;
    EdgeLines lines;
    EdgeIndexes edgeOf(surfaces.size());
    std::vector<PendingEdge> pending;
    registerEdges(surfaces, lines, edgeOf, pending, counts);
    counts.axialLines = int(lines.lines.size());
    // Non-axial edges by length, shortest first, with std::sort as q3map2 (std::ranges::sort): its
    // ties fall as libstdc++'s introsort leaves them, which is deterministic, and an edge of equal
    // length registered earlier decides the line's origin and direction.
    std::sort(pending.begin(), pending.end(),
              [](const PendingEdge& a, const PendingEdge& b) { return a.length < b.length; });
    for (const PendingEdge& e : pending) {
        const int line = lines.add(e.v1, e.v2, counts);
        if (e.vert >= 0) edgeOf[e.surface][size_t(e.vert)] = line;
    }
    counts.nonAxialLines = int(lines.lines.size()) - counts.axialLines;
    for (size_t s = 0; s < surfaces.size(); ++s) {
        DrawSurface& ds = surfaces[s];
        if (skipped(ds) || ds.kind != SurfaceKind::Face) continue;
        fixFace(ds, edgeOf[s], lines, counts);
        if (!fixBrokenFace(ds)) {
            ++counts.broken;
            ds.kind = SurfaceKind::Bad;
            ds.verts.clear();
            ds.tjunctionVerts.clear();
        }
    }
    return counts;
}

}  // namespace q3::bspstage
