// An independent check of a PVS: the clusters of two points whose straight segment meets no solid
// brush must see each other. Works from the BSP alone (nodes, leafs, brushes, brush sides,
// planes and shader contents), sharing nothing with the vis code.
#pragma once

#include "bspfile.h"
#include "vec3.h"

#include <vector>

namespace q3::vis::test {

class SolidWorld {
public:
    explicit SolidWorld(const bsp::Bsp& bsp);

    // The cluster of the leaf holding `p` (-1 in solid leafs).
    int clusterAt(Vec3 p) const;
    // True when the segment stays more than `margin` units away from every solid brush of the
    // world model (a point is a segment of length zero).
    bool segmentClear(Vec3 a, Vec3 b, float margin) const;

    Vec3 mins, maxs;  // the world model's bounds

private:
    struct HalfSpace {
        Vec3 normal;
        float dist;
    };
    struct SolidBrush {
        std::vector<HalfSpace> sides;
    };
    const bsp::Bsp& bsp_;
    std::vector<SolidBrush> brushes_;
};

// Whether cluster `from` sees cluster `to` in a visibility lump.
bool lumpSees(const std::vector<uint8_t>& lump, int from, int to);

}  // namespace q3::vis::test
