// Model triangles merged before autoclip makes brushes of them (q3map2 model.cpp
// windingMergeOthers, windingMergeConvex): coplanar ones into convex polygons, one brush per
// polygon instead of one per triangle; for the backplane modes, polygons extruded along one
// direction into convex volumes whose outline seen along it stays convex.
#pragma once

#include <vector>

#include "dvec3.h"

namespace q3::bspstage {

struct ClipFace {
    DPlane plane;
    std::vector<DVec3> points;
    int surface = 0;
};

struct ClipWinding {
    DPlane plane;               // of the first triangle, (c - a) x (b - a)
    std::vector<DVec3> points;  // convex, in the triangles' winding order (seen along `extrusion`)
    int surface = 0;            // index of the model surface the first triangle came from
    // Bounds with x measured along the spatial sort direction, y and z as they are.
    DVec3 mins, maxs;
    // Volume merging: the extrusion direction and the polygons that make the volume's front.
    DVec3 extrusion;
    std::vector<ClipFace> fronts;

    bool planar() const { return fronts.size() <= 1; }
};

// A triangle as a winding; false when its points give no plane.
bool clipTriangleWinding(const DVec3& a, const DVec3& b, const DVec3& c, int surface, ClipWinding& out);

// Merges windings that share an edge (corners within 0.001), lie within 0.05 of each other's plane, face the same
// way and stay convex, pass after pass until nothing merges. Returns them in the order brushes are
// made from them.
std::vector<ClipWinding> mergeCoplanarWindings(std::vector<ClipWinding> set);

// Merges windings (each with its extrusion and fronts set) that share an edge seen along the first
// one's extrusion, keep that outline convex and whose fronts do not cut each other. `set` comes in
// the order mergeCoplanarWindings gives.
std::vector<ClipWinding> mergeConvexVolumes(std::vector<ClipWinding> set);

}  // namespace q3::bspstage
