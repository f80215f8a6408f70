#include "winding.h"

#include <array>
#include <cfloat>
#include <cmath>

namespace q3::bspstage {
namespace {

// Clipping never trusts a point closer than this to the plane to be on one side: it would only
// produce slivers (q3map2's ChopWindingInPlaceAccu minimum).
constexpr double kMinimumEpsilon = double(FLT_EPSILON) * 0.5;
constexpr double kTinyEdge = 0.2;
constexpr double kWeldDistance = 0.1;
constexpr double kWeldIntegerSnap = 0.01;

// Compared as 32-bit floats, as q3map2 does: for normals like (1 1 1)/sqrt(3) the first axis wins
// whatever the last bits of the double components are, which fixes the winding's first point.
int dominantAxis(const DVec3& n, float floor) {
    int axis = -1;
    float best = floor;
    for (int i = 0; i < 3; ++i) {
        const float v = float(std::fabs(n[i]));
        if (v > best) {
            best = v;
            axis = i;
        }
    }
    return axis;
}

// Two arithmetics, as in q3map2: brush windings are built in double precision (the "accu"
// functions); every other winding is a 32-bit float polygon, with distances computed in floats
// and split points rounded to floats. Reproducing the float rounding keeps portal coordinates
// and near-epsilon decisions identical to q3map2's.
enum class Precision { Double, Float };

double distanceTo(const DPlane& plane, const DVec3& p, Precision precision) {
    if (precision == Precision::Double) return plane.distanceTo(p);
    return double(dot(plane.normal.toFloat(), p.toFloat()) - float(plane.dist));
}

// The intersection of the segment p1-p2 with the plane; exact on axial components.
DVec3 splitPoint(const DVec3& p1, const DVec3& p2, double d1, double d2, const DPlane& plane, Precision precision) {
    const bool inFloat = precision == Precision::Float;
    const double t = inFloat ? double(float(d1) / (float(d1) - float(d2))) : d1 / (d1 - d2);
    DVec3 mid;
    for (int j = 0; j < 3; ++j) {
        if (plane.normal[j] == 1)
            mid[j] = plane.dist;
        else if (plane.normal[j] == -1)
            mid[j] = -plane.dist;
        else if (inFloat)
            mid[j] = double(float(p1[j] + t * double(float(p2[j]) - float(p1[j]))));
        else
            mid[j] = p1[j] + t * (p2[j] - p1[j]);
    }
    return mid;
}

// Each point's distance and side, the first point repeated at the end. Held inline for the
// windings met in practice: clipping is the hottest path of -bsp and must not allocate.
class Classified {
public:
    Classified(const Winding& w, const DPlane& plane, double epsilon, Precision precision) {
        if (w.size() + 1 > kInline) {
            heapDists_.resize(w.size() + 1);
            heapSides_.resize(w.size() + 1);
            dists = heapDists_.data();
            sides = heapSides_.data();
        }
        for (size_t i = 0; i < w.size(); ++i) {
            const double d = distanceTo(plane, w[i], precision);
            dists[i] = d;
            sides[i] = d > epsilon ? PlaneSide::Front : (d < -epsilon ? PlaneSide::Back : PlaneSide::On);
            ++counts[int(sides[i])];
        }
        dists[w.size()] = dists[0];
        sides[w.size()] = sides[0];
    }
    Classified(const Classified&) = delete;
    Classified& operator=(const Classified&) = delete;

    double* dists = inlineDists_.data();
    PlaneSide* sides = inlineSides_.data();
    int counts[3] = {0, 0, 0};

private:
    static constexpr size_t kInline = 32;
    std::array<double, kInline> inlineDists_;
    std::array<PlaneSide, kInline> inlineSides_;
    std::vector<double> heapDists_;
    std::vector<PlaneSide> heapSides_;
};

void chop(Winding& w, const DPlane& plane, double epsilon, Precision precision) {
    const Classified c(w, plane, epsilon, precision);
    if (!c.counts[int(PlaneSide::Front)]) {
        w.clear();
        return;
    }
    if (!c.counts[int(PlaneSide::Back)]) return;
    Winding front;
    front.reserve(w.size() + 4);
    for (size_t i = 0; i < w.size(); ++i) {
        if (c.sides[i] == PlaneSide::On) {
            front.push_back(w[i]);
            continue;
        }
        if (c.sides[i] == PlaneSide::Front) front.push_back(w[i]);
        if (c.sides[i + 1] == PlaneSide::On || c.sides[i + 1] == c.sides[i]) continue;
        front.push_back(splitPoint(w[i], w[(i + 1) % w.size()], c.dists[i], c.dists[i + 1], plane, precision));
    }
    w.swap(front);
}

double weldComponent(double a, double b) {
    const double ai = std::rint(a), bi = std::rint(b);
    const double ad = std::fabs(ai - a), bd = std::fabs(bi - b);
    if (ad < bd) return ad < kWeldIntegerSnap ? ai : a;
    return bd < kWeldIntegerSnap ? bi : b;
}

// Outward direction of the edge from `a` to `b` of a clockwise winding on a plane with `normal`.
DVec3 edgeOutward(const DVec3& a, const DVec3& b, const DVec3& normal) { return normalize(cross(normal, b - a)); }

}  // namespace

Winding baseWindingForPlane(const DPlane& plane) {
    const int axis = dominantAxis(plane.normal, -1e30f);
    const Vec3 normal = plane.normal.toFloat();
    Vec3 up = axis == 2 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
    up -= normal * dot(up, normal);
    up = (DVec3(up) / length(DVec3(up))).toFloat();  // q3map2 normalises through doubles
    const Vec3 org = normal * float(plane.dist);
    Vec3 right = cross(up, normal);
    up *= float(kMaxWorldCoord * 2);
    right *= float(kMaxWorldCoord * 2);
    return {DVec3(org - right + up), DVec3(org + right + up), DVec3(org + right - up), DVec3(org - right - up)};
}

Winding baseWindingForPlaneInBounds(const DPlane& plane, const DBounds& bounds) {
    const int axis = dominantAxis(plane.normal, 0.56f);
    if (axis < 0 || bounds.empty()) return {};
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const DVec3 centre = (bounds.mins + bounds.maxs) * 0.5, half = (bounds.maxs - bounds.mins) * 0.5;
    const double alongA = plane.normal[axis] > 0 ? half[a] : -half[a];
    // Corners of the bounds' footprint across the dominant axis, lifted onto the plane along it.
    Winding w;
    for (const auto [sr, su] : {std::pair{-1, 1}, std::pair{1, 1}, std::pair{1, -1}, std::pair{-1, -1}}) {
        DVec3 p;
        p[b] = centre[b] - sr * half[b];
        p[a] = centre[a] + su * alongA;
        p[axis] = (plane.dist - plane.normal[a] * p[a] - plane.normal[b] * p[b]) / plane.normal[axis];
        w.push_back(p);
    }
    return w;
}

void chopWindingInPlace(Winding& w, const DPlane& plane, double epsilon) { chop(w, plane, epsilon, Precision::Float); }

void chopWindingInPlaceAccurate(Winding& w, const DPlane& plane, double epsilon) {
    chop(w, plane, std::max(epsilon, kMinimumEpsilon), Precision::Double);
}

std::pair<Winding, Winding> clipWindingStrict(const Winding& w, const DPlane& plane, double epsilon) {
    const Classified c(w, plane, epsilon, Precision::Float);
    if (!c.counts[int(PlaneSide::Front)] && !c.counts[int(PlaneSide::Back)]) return {};
    if (!c.counts[int(PlaneSide::Front)]) return {Winding{}, w};
    if (!c.counts[int(PlaneSide::Back)]) return {w, Winding{}};
    Winding front, back;
    front.reserve(w.size() + 4);
    back.reserve(w.size() + 4);
    for (size_t i = 0; i < w.size(); ++i) {
        if (c.sides[i] == PlaneSide::On) {
            front.push_back(w[i]);
            back.push_back(w[i]);
            continue;
        }
        (c.sides[i] == PlaneSide::Front ? front : back).push_back(w[i]);
        if (c.sides[i + 1] == PlaneSide::On || c.sides[i + 1] == c.sides[i]) continue;
        const DVec3 mid = splitPoint(w[i], w[(i + 1) % w.size()], c.dists[i], c.dists[i + 1], plane, Precision::Float);
        front.push_back(mid);
        back.push_back(mid);
    }
    return {std::move(front), std::move(back)};
}

std::pair<Winding, Winding> clipWinding(const Winding& w, const DPlane& plane, double epsilon) {
    auto result = clipWindingStrict(w, plane, epsilon);
    if (result.first.empty() && result.second.empty()) result.second = w;
    return result;
}

PlaneSide windingOnPlaneSide(const Winding& w, const DPlane& plane) {
    bool front = false, back = false;
    // distanceTo(.., Precision::Float) with the plane's float copy made once (the hottest loop of -bsp).
    const Vec3 normal = plane.normal.toFloat();
    const float dist = float(plane.dist);
    for (const DVec3& p : w) {
        const double d = double(dot(normal, p.toFloat()) - dist);
        if (d < -kOnEpsilon) {
            if (front) return PlaneSide::Cross;
            back = true;
        } else if (d > kOnEpsilon) {
            if (back) return PlaneSide::Cross;
            front = true;
        }
    }
    if (back) return PlaneSide::Back;
    if (front) return PlaneSide::Front;
    return PlaneSide::On;
}

bool windingIsTiny(const Winding& w) {
    int edges = 0;
    for (size_t i = w.size() - 1, j = 0; j < w.size(); i = j, ++j)
        if (length(w[j] - w[i]) > kTinyEdge && ++edges == 3) return false;
    return true;
}

double windingArea(const Winding& w) {
    double total = 0;
    for (size_t i = 2; i < w.size(); ++i) total += 0.5 * length(cross(w[i - 1] - w[0], w[i] - w[0]));
    return total;
}

DVec3 windingCenter(const Winding& w) {
    DVec3 sum;
    for (const DVec3& p : w) sum += p;
    return w.empty() ? sum : sum / double(w.size());
}

DBounds windingBounds(const Winding& w) {
    DBounds b;
    for (const DVec3& p : w) b.add(p);
    return b;
}

Winding reverseWinding(const Winding& w) { return Winding(w.rbegin(), w.rend()); }

DPlane windingPlane(const Winding& w) {
    const DVec3 normal = normalize(cross(w[2] - w[0], w[1] - w[0]));
    return {normal, dot(w[0], normal)};
}

void weldShortEdges(Winding& w) {
    bool changed = true;
    while (changed && w.size() >= 2) {
        changed = false;
        for (size_t i = w.size() - 1, j = 0; j < w.size(); i = j, ++j) {
            if (length(w[i] - w[j]) < kWeldDistance) {
                w[i] = {weldComponent(w[i].x, w[j].x), weldComponent(w[i].y, w[j].y), weldComponent(w[i].z, w[j].z)};
                w.erase(w.begin() + std::ptrdiff_t(j));
                changed = true;
                break;
            }
        }
    }
}

void addWindingToConvexHull(const Winding& w, Winding& hull, const DVec3& normal) {
    if (hull.empty()) {
        hull = w;
        return;
    }
    for (const DVec3& p : w) {
        const size_t n = hull.size();
        std::vector<bool> facesPoint(n);
        bool outside = false;
        for (size_t j = 0; j < n; ++j) {
            const DVec3& a = hull[j];
            const DVec3 out = edgeOutward(a, hull[(j + 1) % n], normal);
            const double d = dot(p - a, out);
            if (d >= kOnEpsilon) outside = true;
            facesPoint[j] = d >= -kOnEpsilon;
        }
        if (!outside) continue;
        // The edges the point sees form one run; the vertices inside that run leave the hull.
        size_t start = n;
        for (size_t j = 0; j < n; ++j)
            if (facesPoint[j] && !facesPoint[(j + n - 1) % n]) {
                start = j;
                break;
            }
        if (start == n) continue;  // sees every edge: degenerate hull, keep it
        size_t end = start;
        while (facesPoint[end]) end = (end + 1) % n;
        // The new point first, then the kept vertices in order (q3map2's order).
        Winding grown{p};
        for (size_t k = end;; k = (k + 1) % n) {
            grown.push_back(hull[k]);
            if (k == start) break;
        }
        hull.swap(grown);
    }
}

bool coplanarWindingsIntersect(const Winding& a, const Winding& b, const DVec3& normal) {
    auto separatedByEdgeOf = [&](const Winding& edges, const Winding& points) {
        for (size_t j = 0; j < edges.size(); ++j) {
            const DVec3 out = edgeOutward(edges[j], edges[(j + 1) % edges.size()], normal);
            bool allOutside = true;
            for (const DVec3& p : points)
                if (dot(p - edges[j], out) <= -kOnEpsilon) {
                    allOutside = false;
                    break;
                }
            if (allOutside) return true;
        }
        return false;
    };
    return !separatedByEdgeOf(a, b) && !separatedByEdgeOf(b, a);
}

}  // namespace q3::bspstage
