#include "solid_shell.h"

#include <algorithm>
#include <cmath>

#include "bsp_tree.h"

namespace q3::light {

bool SolidShell::segmentMeetsCell(size_t cell, const DVec3& org, const DVec3& dir, double t0, double t1) const {
    for (uint32_t i = firstPlane[cell]; i < firstPlane[cell + 1]; ++i) {
        const ConvexCell::Plane& p = planes[i];
        const double along = dot(p.normal, dir);
        const double room = p.dist - dot(p.normal, org);
        if (along > 0)
            t1 = std::min(t1, room / along);
        else if (along < 0)
            t0 = std::max(t0, room / along);
        else if (room < 0)
            return false;
        if (t0 > t1) return false;
    }
    return true;
}

bool SolidShell::segmentMeetsAnyCell(Vec3 from, Vec3 to) const {
    const DVec3 org(from), dir = DVec3(to) - DVec3(from);
    for (size_t c = 0; c < boxes.size(); ++c)
        if (segmentMeetsCell(c, org, dir, 0, 1)) return true;
    return false;
}

SolidShell solidShellOf(const bsp::Model* world, const BspTree& tree) {
    SolidShell shell;
    if (!world) return shell;
    // Cells are cut from the world's box and a pad; segments are tested when both ends lie within
    // half the pad of the world, so they never reach the cut box's sides.
    constexpr double kPad = 64;
    DVec3 lo{world->mins[0], world->mins[1], world->mins[2]}, hi{world->maxs[0], world->maxs[1], world->maxs[2]};
    double extent = 0;
    for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]) || lo[k] > hi[k]) return shell;
        lo[k] -= kPad, hi[k] += kPad;
        extent = std::max({extent, std::fabs(lo[k]), std::fabs(hi[k])});
    }
    if (extent > 1e6) return shell;
    // The walk's on-plane epsilon, its split points' rounding (as SolidSegmentTree::hullWalk's
    // margin) and room for the rounding of the segment's own points.
    const double rounding = 0.01 + 1e-5 * extent;
    const double relax = 0.1 + rounding + 0.02;
    const float pad = float(1e-5 * extent);
    for (const ConvexCell& c : tree.solidCells(lo, hi, relax)) {
        const DBounds db = c.bounds();
        Bounds b;
        for (int k = 0; k < 3; ++k) {
            b.mins[k] = std::nextafter(float(db.mins[k]), -INFINITY) - pad;
            b.maxs[k] = std::nextafter(float(db.maxs[k]), INFINITY) + pad;
        }
        shell.boxes.push_back(b);
        shell.firstPlane.push_back(uint32_t(shell.planes.size()));
        // The cell's faces come in the order the tree's planes cut it, the deepest last; a segment
        // that misses the cell mostly leaves it by one of those (the wall it starts beside), and
        // the clip's answer does not depend on the order: the deepest are asked first.
        const std::vector<ConvexCell::Plane> cellPlanes = c.planes();
        shell.planes.insert(shell.planes.end(), cellPlanes.rbegin(), cellPlanes.rend());
    }
    if (shell.boxes.empty()) return shell;
    shell.firstPlane.push_back(uint32_t(shell.planes.size()));
    shell.region = Bounds{(lo + DVec3::splat(kPad / 2)).toFloat(), (hi - DVec3::splat(kPad / 2)).toFloat()};
    return shell;
}

}  // namespace q3::light
