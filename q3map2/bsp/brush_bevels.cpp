// Bevel sides: collision code expands brushes by axis-aligned boxes, which needs every axial and
// edge-aligned supporting plane present (q3map2 map.cpp AddBrushBevels).
#include <cmath>

#include "bsp_brushes.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

// Surface flags a bevel inherits from the sides it touches (footstep and damage behaviour).
constexpr uint32_t kBevelSurfaceFlagsMask = surfaceflags::NoDamage | surfaceflags::Slick | surfaceflags::Flesh |
                                            surfaceflags::MetalSteps | surfaceflags::NoSteps | surfaceflags::Dust |
                                            surfaceflags::NoOb;
constexpr double kBevelEpsilon = 0.1;

bool planesEqual(const MapPlane& p, const DPlane& plane, const PlaneEpsilons& eps) {
    auto close = [](double a, double b, double e) { return a == b || std::fabs(a - b) < e; };
    return close(p.dist(), plane.dist, eps.distance) && close(p.normal().x, plane.normal.x, eps.normal) &&
           close(p.normal().y, plane.normal.y, eps.normal) && close(p.normal().z, plane.normal.z, eps.normal);
}

bool isAxialDirection(const DVec3& v) {
    for (int i = 0; i < 3; ++i) {
        const int next = (i + 1) % 3;
        if (v[i] == -1.0 || v[i] == 1.0 || (v[i] == 0.0 && v[next] == 0.0)) return true;
    }
    return false;
}

int addAxialBevels(Brush& brush, PlaneSet& planes, int snap) {
    int added = 0;
    int order = 0;
    for (int axis = 0; axis < 3; ++axis) {
        for (int dir = -1; dir <= 1; dir += 2, ++order) {
            size_t i = 0;
            for (; i < brush.sides.size(); ++i)
                if (planes[brush.sides[i].planeNum].normal()[axis] == double(dir)) break;
            if (i == brush.sides.size()) {
                DPlane plane{DVec3::axis(axis, dir), dir == 1 ? brush.bounds.maxs[axis] : -brush.bounds.mins[axis]};
                plane.dist = double(float(plane.dist));
                if (snap > 0) {
                    // -snap: the bevel moves inwards to a multiple of N (fewer distinct planes).
                    const float n = float(snap);
                    plane.dist = dir == 1 ? double(std::floor(float(brush.bounds.maxs[axis]) / n) * n)
                                          : double(-(std::ceil(float(brush.bounds.mins[axis]) / n) * n));
                }
                BrushSide bevel;
                bevel.planeNum = planes.find(plane);
                bevel.contentFlags = brush.sides[0].contentFlags;
                bevel.bevel = true;
                // q3map2 compares the signed plane distance with the coordinate, so only +axis
                // bevels (or bevels at 0) ever inherit flags.
                for (const BrushSide& side : brush.sides) {
                    for (const DVec3& p : side.winding) {
                        if (std::fabs(plane.dist - p[axis]) < kBevelEpsilon) {
                            bevel.surfaceFlags |= side.surfaceFlags & kBevelSurfaceFlagsMask;
                            break;
                        }
                    }
                }
                brush.sides.push_back(std::move(bevel));
                ++added;
            }
            if (i != size_t(order)) std::swap(brush.sides[size_t(order)], brush.sides[i]);
        }
    }
    return added;
}

// A candidate edge bevel is kept when it is a new plane, no side has a point in front of it and
// no side lies on it.
bool isNewSupportingPlane(Brush& brush, const DPlane& plane, uint32_t edgeSurfaceFlags, const PlaneSet& planes) {
    for (BrushSide& side : brush.sides) {
        if (planesEqual(planes[side.planeNum], plane, planes.epsilons())) {
            if (side.bevel) side.surfaceFlags |= edgeSurfaceFlags & kBevelSurfaceFlagsMask;
            return false;
        }
        if (side.winding.empty()) continue;
        double minBack = 0;
        for (const DVec3& p : side.winding) {
            const double d = double(dot(plane.normal.toFloat(), p.toFloat()) - float(plane.dist));
            if (d > kBevelEpsilon) return false;
            minBack = std::min(minBack, d);
        }
        if (minBack > -kBevelEpsilon) return false;
    }
    return true;
}

// q3map2 normalises float vectors through doubles; false when the vector was shorter than 0.5.
bool normalizeLikeQ3map2(Vec3& v) {
    const DVec3 d(v);
    const double len = length(d);
    if (len == 0) {
        v = {};
        return false;
    }
    v = (d / len).toFloat();
    return float(len) >= 0.5f;
}

int addEdgeBevels(Brush& brush, PlaneSet& planes) {
    if (brush.sides.size() == 6) return 0;  // a box needs none
    int added = 0;
    for (size_t i = 6; i < brush.sides.size(); ++i) {
        const Winding w = brush.sides[i].winding;  // copied: sides grow below
        const uint32_t surfaceFlags = brush.sides[i].surfaceFlags;
        for (size_t j = 0; j < w.size(); ++j) {
            // In 32-bit floats like q3map2: candidates touching a vertex are accepted or refused
            // by 0.1-unit tests whose outcome can depend on the last bits.
            Vec3 edge = w[j].toFloat() - w[(j + 1) % w.size()].toFloat();
            if (!normalizeLikeQ3map2(edge)) continue;
            DVec3 snapped(edge);
            snapNormal(snapped, planes.epsilons().normal);
            edge = snapped.toFloat();
            if (isAxialDirection(DVec3(edge))) continue;
            for (int axis = 0; axis < 3; ++axis) {
                for (int dir = -1; dir <= 1; dir += 2) {
                    Vec3 normal = cross(edge, DVec3::axis(axis, dir).toFloat());
                    if (!normalizeLikeQ3map2(normal)) continue;
                    const DPlane plane{DVec3(normal), double(dot(w[j].toFloat(), normal))};
                    if (!isNewSupportingPlane(brush, plane, surfaceFlags, planes)) continue;
                    BrushSide bevel;
                    const DVec3 point[1] = {w[j]};
                    bevel.planeNum = planes.find(plane, point);
                    bevel.contentFlags = brush.sides[0].contentFlags;
                    bevel.surfaceFlags = surfaceFlags & kBevelSurfaceFlagsMask;
                    bevel.bevel = true;
                    brush.sides.push_back(std::move(bevel));
                    ++added;
                }
            }
        }
    }
    return added;
}

}  // namespace

std::pair<int, int> addBrushBevels(Brush& brush, PlaneSet& planes, int bevelSnap) {
    const int box = addAxialBevels(brush, planes, bevelSnap);
    const int edge = addEdgeBevels(brush, planes);
    return {box, edge};
}

}  // namespace q3::bspstage
