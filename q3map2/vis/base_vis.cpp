#include "base_vis.h"

#include <tbb/parallel_for.h>

#include <cstdint>
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

// What the pair test reads of every portal, packed: a portal with its winding is about 1 KB, and
// the test runs over all pairs.
struct PortalBound {
    Plane plane;
    Vec3 origin;
    float radius;
    int leaf;
    bool removed;
};

// The planes and spheres of all portals, one array per number, so that the test of one portal's
// sphere against all planes (and of its plane against all spheres) runs several portals at once.
struct SphereColumns {
    std::vector<float> nx, ny, nz, dist, ox, oy, oz, radius;

    explicit SphereColumns(const std::vector<PortalBound>& bounds) {
        for (const PortalBound& b : bounds) {
            nx.push_back(b.plane.normal.x);
            ny.push_back(b.plane.normal.y);
            nz.push_back(b.plane.normal.z);
            dist.push_back(b.plane.dist);
            ox.push_back(b.origin.x);
            oy.push_back(b.origin.y);
            oz.push_back(b.origin.z);
            radius.push_back(b.radius);
        }
    }

    // maybe[j] = 0 when, by the bounding spheres alone, portal j cannot reach in front of p or p
    // cannot reach behind j; 1 otherwise. The sums are those of Plane::distanceTo, term by term.
    void spheresMayFace(const PortalBound& p, std::vector<int32_t>& maybe) const {
        const float px = p.plane.normal.x, py = p.plane.normal.y, pz = p.plane.normal.z, pd = p.plane.dist;
        const float ax = p.origin.x, ay = p.origin.y, az = p.origin.z, pr = p.radius;
        const size_t n = nx.size();
        maybe.resize(n);
        for (size_t j = 0; j < n; ++j) {
            const float jInFront = px * ox[j] + py * oy[j] + pz * oz[j] - pd + radius[j];
            const float pBehind = nx[j] * ax + ny[j] * ay + nz[j] * az - dist[j] - pr;
            maybe[j] = (jInFront >= kOnEpsilon - kSphereSlack) & (pBehind <= -kOnEpsilon + kSphereSlack);
        }
    }
};

// q's winding reaches in front of p's plane, and p's winding reaches behind q's plane. The points
// are only looked at when a sphere straddles the plane.
bool facesForward(const VisPortal& p, const PortalBound& pb, const VisPortal& q, const PortalBound& qb) {
    if (pb.plane.distanceTo(qb.origin) - qb.radius <= kOnEpsilon + kSphereSlack) {
        bool qInFront = false;
        for (Vec3 point : q.winding.view())
            if (p.plane.distanceTo(point) > kOnEpsilon) {
                qInFront = true;
                break;
            }
        if (!qInFront) return false;
    }
    if (qb.plane.distanceTo(pb.origin) + pb.radius < -kOnEpsilon - kSphereSlack) return true;
    for (Vec3 point : p.winding.view())
        if (q.plane.distanceTo(point) < -kOnEpsilon) return true;
    return false;
}

// Marks in `flood` every portal reachable from `leaf` through portals of `front`. A leaf is
// scanned once: a second visit could only find its front portals flooded already.
void floodFrom(const VisGraph& graph, const std::vector<PortalBound>& bounds, int leaf, const uint64_t* front,
               uint64_t* flood, std::vector<int>& pending, std::vector<uint8_t>& reached) {
    std::fill(reached.begin(), reached.end(), 0);
    pending.assign(1, leaf);
    reached[static_cast<size_t>(leaf)] = 1;
    while (!pending.empty()) {
        const int l = pending.back();
        pending.pop_back();
        for (int pnum : graph.leafs[static_cast<size_t>(l)].portals) {
            const size_t p = static_cast<size_t>(pnum);
            if (!testBit(front, p) || bounds[p].removed) continue;
            setBit(flood, p);
            const size_t next = static_cast<size_t>(bounds[p].leaf);
            if (!reached[next]) {
                reached[next] = 1;
                pending.push_back(bounds[p].leaf);
            }
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
    std::vector<PortalBound> bounds(n);
    for (size_t i = 0; i < n; ++i) {
        const VisPortal& p = graph.portals[i];
        bounds[i] = {p.plane, p.origin, p.radius, p.leaf, p.removed};
    }
    const SphereColumns columns(bounds);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16), [&](const tbb::blocked_range<size_t>& range) {
        std::vector<uint64_t> front(base.flood.words());
        std::vector<int> pending;
        std::vector<uint8_t> reached(graph.leafs.size());
        std::vector<int32_t> maybe;
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const VisPortal& p = graph.portals[i];
            if (p.removed) {
                if (advance) advance();
                continue;
            }
            std::fill(front.begin(), front.end(), 0);
            columns.spheresMayFace(bounds[i], maybe);
            for (size_t j = 0; j < n; ++j) {
                if (!maybe[j] || j == i || bounds[j].removed) continue;
                const VisPortal& q = graph.portals[j];
                if (beyondFarPlane(p, q, farPlane)) continue;
                if (facesForward(p, bounds[i], q, bounds[j])) setBit(front.data(), j);
            }
            floodFrom(graph, bounds, p.leaf, front.data(), base.flood.row(i), pending, reached);
            base.mightSee[i] = static_cast<int>(countBits(base.flood.row(i), base.flood.words()));
            if (advance) advance();
        }
    });
    return base;
}

}  // namespace q3::vis
