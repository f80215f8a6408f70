// The map's plane list, built the way q3map2 builds it (map.cpp FindFloatPlane): planes come in
// pairs (n, n^1 = n flipped; for axial planes the positive normal gets the even index), candidates
// are snapped first (near-axial normals, near-integer axial distances) and matched within the
// normal and distance epsilons through a hash on the integer distance.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "dvec3.h"

namespace q3::bspstage {

enum PlaneType : int { PlaneX = 0, PlaneY = 1, PlaneZ = 2, PlaneNonAxial = 3 };

struct MapPlane {
    DPlane plane;  // stored with 32-bit float precision, as q3map2 keeps them
    int type = PlaneNonAxial;

    const DVec3& normal() const { return plane.normal; }
    double dist() const { return plane.dist; }
};

struct PlaneEpsilons {
    double normal = 0.00005;  // -ne
    double distance = 0.005;  // -de
};

// 0/1/2 when the normal is exactly along X/Y/Z (either sign), else PlaneNonAxial.
int planeTypeForNormal(const DVec3& normal);
// Zeroes near-zero components (two under 0.00025, then any under `normalEpsilon`) and renormalises.
// Returns true when the normal changed.
bool snapNormal(DVec3& normal, double normalEpsilon);
// Snaps `plane` as q3map2 does before a look-up: the normal as above, the distance re-derived
// through the centroid of `points` when the normal moved, and axial distances within the distance
// epsilon of an integer rounded to it.
void snapPlane(DPlane& plane, std::span<const DVec3> points, const PlaneEpsilons& epsilons);

class PlaneSet {
public:
    explicit PlaneSet(PlaneEpsilons epsilons = {});

    // Index of the plane matching (normal, dist), created (with its flipped twin) when none matches.
    // Every point given must lie within the distance epsilon of a match. -1 when the normal is
    // shorter than 0.5 ("bad normal").
    int find(const DPlane& plane, std::span<const DVec3> points = {});
    // The plane through three points as q3map2 orients it (normal = (c - a) x (b - a)).
    int fromPoints(const DVec3& a, const DVec3& b, const DVec3& c);

    const MapPlane& operator[](int index) const { return planes_[size_t(index)]; }
    int size() const { return int(planes_.size()); }
    const PlaneEpsilons& epsilons() const { return epsilons_; }

private:
    static constexpr int kHashSize = 8192;
    static int hashOf(double dist);
    bool matches(const MapPlane& candidate, const DPlane& plane, std::span<const DVec3> points) const;
    int create(const DPlane& plane);
    void addToHash(int index);

    PlaneEpsilons epsilons_;
    std::vector<MapPlane> planes_;
    std::vector<int> hashNext_;            // per plane: next plane in its bin, -1 at the end
    std::array<int, kHashSize> hashHead_;  // per bin: most recent plane, -1 when empty
};

}  // namespace q3::bspstage
