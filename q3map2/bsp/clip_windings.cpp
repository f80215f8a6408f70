#include "clip_windings.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace q3::bspstage {
namespace {

constexpr double kOnEpsilon = 0.1;

// q3map2 sorts and bounds merge candidates along this direction, in floats.
float spatialDistance(const DVec3& p) {
    const float x = float(p.x), y = float(p.y), z = float(p.z);
    return 0.786868f * x + 0.316861f * y + 0.529564f * z;
}

void extend(ClipWinding& w, const DVec3& p) {
    const DVec3 q{spatialDistance(p), double(float(p.y)), double(float(p.z))};
    w.mins = vmin(w.mins, q);
    w.maxs = vmax(w.maxs, q);
}

bool boundsTouch(const ClipWinding& a, const ClipWinding& b, double epsilon) {
    for (int i = 0; i < 3; ++i)
        if (a.mins[i] > b.maxs[i] + epsilon || a.maxs[i] < b.mins[i] - epsilon) return false;
    return true;
}

// q3map2 compares corners as floats, each component within 0.001.
bool sameCorner(const DVec3& a, const DVec3& b) {
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(float(a[i]) - float(b[i])) < 0.001f)) return false;
    return true;
}

size_t nextOf(size_t i, size_t n) { return i + 1 == n ? 0 : i + 1; }
size_t prevOf(size_t i, size_t n) { return i == 0 ? n - 1 : i - 1; }

// The plane with normal (along x (to - from)) normalised, through `through` (from or to).
DPlane edgePlane(const DVec3& along, const DVec3& from, const DVec3& to, const DVec3& through) {
    DPlane p{normalize(cross(along, to - from)), 0};
    p.dist = dot(p.normal, through);
    return p;
}

// Tries to join `other` into `first` along a shared edge (first's prev->next runs other's
// next->prev), if the outline seen along `along` stays convex at both ends. True when joined.
bool joinAlongEdge(ClipWinding& first, const ClipWinding& other, const DVec3& along) {
    std::vector<DVec3>& w = first.points;
    const std::vector<DVec3>& o = other.points;
    const size_t n = w.size(), m = o.size();
    for (size_t next = 0; next < n; ++next) {
        const size_t prev = prevOf(next, n);
        for (size_t nex = 0; nex < m; ++nex) {
            const size_t pre = prevOf(nex, m);
            if (!sameCorner(w[prev], o[nex]) || !sameCorner(w[next], o[pre])) continue;
            // The first shared edge decides: joined if both its ends stay convex.
            const DVec3& nnext = w[nextOf(next, n)];
            const DVec3& pprev = w[prevOf(prev, n)];
            const DVec3& nnex = o[nextOf(nex, m)];
            const DVec3& ppre = o[prevOf(pre, m)];
            double pd = edgePlane(along, pprev, nnex, pprev).distanceTo(w[prev]);
            double nd = edgePlane(along, ppre, nnext, nnext).distanceTo(w[next]);
            if (pd <= -kOnEpsilon || nd <= -kOnEpsilon) return false;
            // other's points strictly between its copies of prev and next, in its order.
            std::vector<DVec3> between;
            for (size_t k = nextOf(nex, m); k != pre; k = nextOf(k, m)) between.push_back(o[k]);
            w.insert(w.begin() + std::ptrdiff_t(next), between.begin(), between.end());
            size_t iprev = prevOf(next, w.size());
            size_t inext = (next + between.size()) % w.size();
            // Collinear corners go, the higher index first so the lower stays valid.
            if (iprev > inext) {
                std::swap(iprev, inext);
                std::swap(pd, nd);
            }
            if (std::fabs(nd) < kOnEpsilon) w.erase(w.begin() + std::ptrdiff_t(inext));
            if (std::fabs(pd) < kOnEpsilon && w.size() > 3) w.erase(w.begin() + std::ptrdiff_t(iprev));
            return true;
        }
    }
    return false;
}

bool sameFacing(const DVec3& a, const DVec3& b) {
    return std::fabs(a.x - b.x) < 0.1 && std::fabs(a.y - b.y) < 0.1 && std::fabs(a.z - b.z) < 0.1;
}

// Coplanar: within 0.05 of the first's plane and facing its way.
bool coplanarCandidate(const ClipWinding& first, const ClipWinding& other) {
    const bool offPlane = std::any_of(other.points.begin(), other.points.end(), [&](const DVec3& p) {
        return std::fabs(first.plane.distanceTo(p)) > kOnEpsilon / 2;
    });
    return !offPlane && sameFacing(first.plane.normal, other.plane.normal);
}

// Volumes: the other can be extruded the first's way, and no corner of the first's fronts lies in
// front of the other's.
bool volumeCandidate(const ClipWinding& first, const ClipWinding& other) {
    if (other.planar() ? dot(other.plane.normal, first.extrusion) < 0.05 : other.extrusion != first.extrusion)
        return false;
    for (const ClipFace& mine : first.fronts)
        for (const DVec3& p : mine.points)
            for (const ClipFace& theirs : other.fronts)
                if (theirs.plane.distanceTo(p) > kOnEpsilon) return false;
    return true;
}

// `set` is sorted by decreasing mins.x and searched from its end. Returns true if anything joined.
template <bool volumes>
bool mergeOthers(ClipWinding& first, std::vector<ClipWinding>& set) {
    bool merged = false;
    for (size_t k = set.size(); k-- > 0;) {
        ClipWinding& other = set[k];
        if (other.mins.x > first.maxs.x + 1) break;
        if (!boundsTouch(other, first, 1)) continue;
        if (volumes ? !volumeCandidate(first, other) : !coplanarCandidate(first, other)) continue;
        if (!joinAlongEdge(first, other, volumes ? first.extrusion : first.plane.normal)) continue;
        first.mins = vmin(first.mins, other.mins);
        first.maxs = vmax(first.maxs, other.maxs);
        if (volumes)
            for (ClipFace& f : other.fronts) first.fronts.push_back(std::move(f));
        set.erase(set.begin() + std::ptrdiff_t(k));
        merged = true;
        k = set.size();  // restart from the end
    }
    return merged;
}

// Passes over `set` (next taken from its end) until one merges nothing; returns the windings, the
// last taken first.
template <bool volumes>
std::vector<ClipWinding> mergePasses(std::vector<ClipWinding> set) {
    std::vector<ClipWinding> done;
    bool somethingMerged = false;
    for (;;) {
        if (set.empty()) {
            // A pass ends: what was taken goes back, first taken at the end, for another pass.
            std::swap(set, done);
            std::reverse(set.begin(), set.end());
            if (!std::exchange(somethingMerged, false)) break;
        }
        done.push_back(std::move(set.back()));
        set.pop_back();
        somethingMerged |= mergeOthers<volumes>(done.back(), set);
    }
    return set;
}

}  // namespace

bool clipTriangleWinding(const DVec3& a, const DVec3& b, const DVec3& c, int surface, ClipWinding& out) {
    const DVec3 n = cross(c - a, b - a);
    const double len = length(n);
    if (len == 0) return false;
    out.plane.normal = n / len;
    out.plane.dist = dot(a, out.plane.normal);
    out.points = {a, b, c};
    out.surface = surface;
    out.mins = DVec3{1e300, 1e300, 1e300};
    out.maxs = DVec3{-1e300, -1e300, -1e300};
    for (const DVec3& p : out.points) extend(out, p);
    return true;
}

std::vector<ClipWinding> mergeCoplanarWindings(std::vector<ClipWinding> set) {
    std::stable_sort(set.begin(), set.end(), [](const ClipWinding& a, const ClipWinding& b) { return a.mins.x > b.mins.x; });
    return mergePasses<false>(std::move(set));
}

std::vector<ClipWinding> mergeConvexVolumes(std::vector<ClipWinding> set) {
    return mergePasses<true>(std::move(set));
}

}  // namespace q3::bspstage
