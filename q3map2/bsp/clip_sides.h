// The planes of one autoclip brush (q3map2 model.cpp ClipSides and the clipModel_* shapes): a front
// polygon, one side plane per edge shaped by the clip mode, and an optional back plane, in the
// arithmetic q3map2 uses (float planes from double points, double side planes rounded on lookup).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "dvec3.h"
#include "plane_set.h"
#include "vec3.h"

namespace q3::bspstage {

// The axis-aligned unit vector nearest `n` (ties to the earlier axis); its index in `axisOut`.
DVec3 axialOf(const DVec3& n, int* axisOut = nullptr);

struct ClipSides {
    DPlane front;
    std::vector<DVec3> points;  // the front polygon
    std::vector<DPlane> sides;  // through points[i] and next(i)
    bool hasBack = false;
    DPlane back;
    std::vector<DVec3> backPoints;  // empty for back planes not parallel to the front
    double clipDepth = 2;

    const DVec3& next(size_t i) const { return points[i + 1 == points.size() ? 0 : i + 1]; }

    // The front plane from the widest corner triple, snapped, the points projected onto it when it
    // moved; false when the polygon is degenerate.
    bool construct(const PlaneEpsilons& epsilons);
    // A merged volume's front is its first face's plane (the faces become sides of their own).
    void constructVolume(const DPlane& firstFace);

    void sidesAlong(const DVec3& direction);
    // The front flipped, moved clipDepth along `direction` behind it.
    void addBack(const DVec3& direction);

    // Sides along the axis nearest the normal, back plane behind.
    void defaultShape();
    // Sides to an apex clipDepth behind the centre, no back plane.
    void pyramid();
    void faceNormals();
    void leaning45();
    // Sides along `direction`; the default shape when the front faces away from it.
    void extruded(const DVec3& direction);
    // Each side takes, of the planes through its edge along the main axis or tilted towards one of
    // the others, the one that leaves the polygon thinnest while facing away from it.
    void axialPyramid(float limitDepth);
    void vertexNormals(const std::array<Vec3, 3>& normals, bool noOutwardCheck);
    // Sides along `direction`; the back plane square to it, at the far corner of `bounds` (maximal
    // extrusion) or of the polygon (axial backplane), or behind the front when that is deeper
    // than `limitDepth`.
    void specialBack(int shape, const DVec3& direction, const DBounds& bounds, float limitDepth);
};

}  // namespace q3::bspstage
