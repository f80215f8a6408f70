#include "base_vis.h"

#include <tbb/parallel_for.h>

#include <cstdlib>
#include <string>

namespace q3::vis {

namespace {

bool beyondFarPlane(const VisPortal& p, const VisPortal& q, const FarPlane& far) {
    if (far.distance == 0 || p.sky || q.sky) return false;
    const float centres = length(p.origin - q.origin);
    switch (far.mode) {
    case 'o': return centres > far.distance;
    case 'e': return centres + p.radius + q.radius > 2.0f * far.distance;
    case 'r': return p.radius + q.radius > far.distance;
    default: return centres - p.radius - q.radius > far.distance;
    }
}

// Slack for the bounding-sphere shortcuts below: the sphere is computed in single precision.
constexpr float kSphereSlack = 0.05f;

// q's winding reaches in front of p's plane, and p's winding reaches behind q's plane.
bool facesForward(const VisPortal& p, const VisPortal& q) {
    // Spheres first: most pairs are decided without looking at a point.
    if (p.plane.distanceTo(q.origin) + q.radius < kOnEpsilon - kSphereSlack) return false;
    if (q.plane.distanceTo(p.origin) - p.radius > -kOnEpsilon + kSphereSlack) return false;
    bool qInFront = false;
    for (Vec3 point : q.winding.view())
        if (p.plane.distanceTo(point) > kOnEpsilon) {
            qInFront = true;
            break;
        }
    if (!qInFront) return false;
    for (Vec3 point : p.winding.view())
        if (q.plane.distanceTo(point) < -kOnEpsilon) return true;
    return false;
}

// Marks in `flood` every portal reachable from `leaf` through portals of `front`.
void floodFrom(const VisGraph& graph, int leaf, const uint64_t* front, uint64_t* flood) {
    std::vector<int> pending{leaf};
    while (!pending.empty()) {
        const int l = pending.back();
        pending.pop_back();
        for (int pnum : graph.leafs[static_cast<size_t>(l)].portals) {
            const VisPortal& p = graph.portals[static_cast<size_t>(pnum)];
            if (p.removed || !testBit(front, static_cast<size_t>(pnum)) || testBit(flood, static_cast<size_t>(pnum)))
                continue;
            setBit(flood, static_cast<size_t>(pnum));
            pending.push_back(p.leaf);
        }
    }
}

}  // namespace

FarPlane FarPlane::parse(std::string_view value) {
    FarPlane far;
    if (value.empty()) return far;
    far.distance = static_cast<float>(std::atof(std::string(value).c_str()));
    far.mode = value.back();
    return far;
}

BaseVis computeBaseVis(const VisGraph& graph, const FarPlane& farPlane, const std::function<void()>& advance) {
    const size_t n = graph.portals.size();
    BaseVis base;
    base.flood = BitMatrix(n, n);
    base.mightSee.assign(n, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16), [&](const tbb::blocked_range<size_t>& range) {
        std::vector<uint64_t> front(base.flood.words());
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const VisPortal& p = graph.portals[i];
            if (p.removed) {
                if (advance) advance();
                continue;
            }
            std::fill(front.begin(), front.end(), 0);
            for (size_t j = 0; j < n; ++j) {
                const VisPortal& q = graph.portals[j];
                if (j == i || q.removed || beyondFarPlane(p, q, farPlane)) continue;
                if (facesForward(p, q)) setBit(front.data(), j);
            }
            floodFrom(graph, p.leaf, front.data(), base.flood.row(i));
            base.mightSee[i] = static_cast<int>(countBits(base.flood.row(i), base.flood.words()));
            if (advance) advance();
        }
    });
    return base;
}

}  // namespace q3::vis
