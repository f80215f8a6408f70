// A convex polyhedron kept as the windings of its faces and cut down one half-space at a time, in
// double precision: the region of a BSP leaf from the planes above it (solid_segment_tree.h).
#pragma once

#include <vector>

#include "dvec3.h"

namespace q3::light {

class ConvexCell {
public:
    struct Plane {
        DVec3 normal;  // the cell keeps dot(normal, x) <= dist
        double dist = 0;
    };

    // The box lo..hi (empty when lo exceeds hi on an axis).
    static ConvexCell box(DVec3 lo, DVec3 hi);

    // The part where dot(normal, x) <= dist (normal need not be unit length). Corners within a
    // relative 1e-12 of the plane count as on it, so a cut never loses a sliver of the cell.
    ConvexCell clipped(DVec3 normal, double dist) const;
    // Whether clipped() would leave every corner where it is.
    bool inside(DVec3 normal, double dist) const;

    bool empty() const { return faces_.empty(); }
    DBounds bounds() const;
    struct Face {
        Plane plane;
        std::vector<DVec3> points;  // a convex polygon on the plane
    };
    const std::vector<Face>& faces() const { return faces_; }
    // The planes of its faces: together they cut out the cell (planes that only touch it at an
    // edge or a corner are left out, which keeps a set no smaller than the cell).
    std::vector<Plane> planes() const;

private:
    std::vector<Face> faces_;
};

}  // namespace q3::light
