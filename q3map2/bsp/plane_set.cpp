#include "plane_set.h"

#include <cmath>

namespace q3::bspstage {
namespace {

// q3map2 rounds near-axial normals with a fixed threshold before the (configurable) epsilon.
constexpr double kAxisSnap = 0.00025;

DPlane toFloatPrecision(const DPlane& p) { return {roundToFloat(p.normal), double(float(p.dist))}; }

bool isOnAxis(const DVec3& n) {
    int zeros = (n.x == 0) + (n.y == 0) + (n.z == 0);
    return zeros == 2;
}

}  // namespace

int planeTypeForNormal(const DVec3& normal) {
    if (normal.x == 1.0 || normal.x == -1.0) return PlaneX;
    if (normal.y == 1.0 || normal.y == -1.0) return PlaneY;
    if (normal.z == 1.0 || normal.z == -1.0) return PlaneZ;
    return PlaneNonAxial;
}

bool snapNormal(DVec3& normal, double normalEpsilon) {
    bool adjusted = false;
    // Two tiny components: the normal is meant to be axial.
    for (auto [a, b] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{2, 1}}) {
        if ((normal[a] != 0.0 || normal[b] != 0.0) && std::fabs(normal[a]) < kAxisSnap &&
            std::fabs(normal[b]) < kAxisSnap) {
            normal[a] = normal[b] = 0.0;
            adjusted = true;
            break;
        }
    }
    for (int i = 0; i < 3; ++i) {
        if (normal[i] != 0.0 && -normalEpsilon < normal[i] && normal[i] < normalEpsilon) {
            normal[i] = 0.0;
            adjusted = true;
        }
    }
    if (adjusted) normal = normalize(normal);
    return adjusted;
}

void snapPlane(DPlane& plane, std::span<const DVec3> points, const PlaneEpsilons& epsilons) {
    if (snapNormal(plane.normal, epsilons.normal) && !points.empty()) {
        DVec3 center;
        for (const DVec3& p : points) center += p;
        center = center / double(points.size());
        plane.dist = dot(plane.normal, center);
    }
    if (isOnAxis(plane.normal)) {
        const double nearest = std::rint(plane.dist);
        if (-epsilons.distance < plane.dist - nearest && plane.dist - nearest < epsilons.distance)
            plane.dist = nearest;
    }
}

PlaneSet::PlaneSet(PlaneEpsilons epsilons) : epsilons_(epsilons) { hashHead_.fill(-1); }

int PlaneSet::hashOf(double dist) { return (kHashSize - 1) & int(std::fabs(dist)); }

bool PlaneSet::matches(const MapPlane& candidate, const DPlane& plane, std::span<const DVec3> points) const {
    // In 32-bit floats, as q3map2 stores and compares planes: a distance 0.005 away from a plane
    // matches or not depending on float rounding, and with it which plane a side ends on.
    auto close = [](double a, double b, double eps) {
        const float fa = float(a), fb = float(b);
        return fa == fb || std::fabs(fa - fb) < float(eps);
    };
    if (!close(candidate.dist(), plane.dist, epsilons_.distance)) return false;
    for (int i = 0; i < 3; ++i)
        if (!close(candidate.normal()[i], plane.normal[i], epsilons_.normal)) return false;
    for (const DVec3& p : points) {
        const Vec3 n = candidate.normal().toFloat();
        const double d = std::fabs(double(dot(n, p.toFloat()) - float(candidate.dist())));
        if (d != 0.0 && d >= epsilons_.distance) return false;
    }
    return true;
}

int PlaneSet::find(const DPlane& input, std::span<const DVec3> points) {
    DPlane plane = toFloatPrecision(input);
    snapPlane(plane, points, epsilons_);
    plane = toFloatPrecision(plane);
    const int hash = hashOf(plane.dist);
    for (int offset = -1; offset <= 1; ++offset) {
        const int bin = (hash + offset) & (kHashSize - 1);
        for (int i = hashHead_[size_t(bin)]; i != -1; i = hashNext_[size_t(i)])
            if (matches(planes_[size_t(i)], plane, points)) return i;
    }
    return create(plane);
}

int PlaneSet::fromPoints(const DVec3& a, const DVec3& b, const DVec3& c) {
    const DVec3 normal = normalize(cross(c - a, b - a));
    if (normal == DVec3{}) return -1;
    const DVec3 points[3] = {roundToFloat(a), roundToFloat(b), roundToFloat(c)};
    return find({normal, dot(a, normal)}, points);
}

int PlaneSet::create(const DPlane& plane) {
    if (length(plane.normal) < 0.5) return -1;
    MapPlane first{plane, planeTypeForNormal(plane.normal)};
    MapPlane second{plane.flipped(), first.type};
    // Axial pairs keep the positive-facing plane even, so nodes can always use the even one.
    const bool negativeAxial =
        first.type != PlaneNonAxial && (plane.normal.x < 0 || plane.normal.y < 0 || plane.normal.z < 0);
    if (negativeAxial) std::swap(first, second);
    const int base = int(planes_.size());
    planes_.push_back(first);
    planes_.push_back(second);
    hashNext_.push_back(-1);
    hashNext_.push_back(-1);
    addToHash(base);
    addToHash(base + 1);
    return negativeAxial ? base + 1 : base;
}

void PlaneSet::addToHash(int index) {
    const int bin = hashOf(planes_[size_t(index)].dist());
    hashNext_[size_t(index)] = hashHead_[size_t(bin)];
    hashHead_[size_t(bin)] = index;
}

}  // namespace q3::bspstage
