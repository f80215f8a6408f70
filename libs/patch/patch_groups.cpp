// Level-of-detail groups: neighbouring patches must pick one subdivision level together.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "patch.h"

namespace q3::patch {
namespace {

constexpr float kShareDistance = 1.0f;  // q3map2's per-axis tolerance for a shared control point

bool sharesControlPoint(const ControlGrid& a, const ControlGrid& b) {
    for (const PatchVertex& p : a.points)
        for (const PatchVertex& q : b.points)
            if (std::fabs(p.xyz.x - q.xyz.x) < kShareDistance && std::fabs(p.xyz.y - q.xyz.y) < kShareDistance &&
                std::fabs(p.xyz.z - q.xyz.z) < kShareDistance)
                return true;
    return false;
}

int findRoot(std::vector<int>& parent, int i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

}  // namespace

std::vector<int> patchLodGroups(std::span<const ControlGrid> grids) {
    const size_t n = grids.size();
    std::vector<Bounds> reach(n);
    for (size_t i = 0; i < n; ++i) {
        reach[i] = controlBounds(grids[i]);
        if (!reach[i].empty()) {
            reach[i].mins -= Vec3::splat(kShareDistance);
            reach[i].maxs += Vec3::splat(kShareDistance);
        }
    }
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            // Boxes grown by the tolerance must overlap before any point pair can be close enough.
            if (!reach[i].intersects(reach[j])) continue;
            const int ri = findRoot(parent, int(i)), rj = findRoot(parent, int(j));
            if (ri == rj || !sharesControlPoint(grids[i], grids[j])) continue;
            parent[std::max(ri, rj)] = std::min(ri, rj);
        }
    std::vector<int> group(n, -1), idOfRoot(n, -1);
    int next = 0;
    for (size_t i = 0; i < n; ++i) {
        const int root = findRoot(parent, int(i));
        if (idOfRoot[root] < 0) idOfRoot[root] = next++;
        group[i] = idOfRoot[root];
    }
    return group;
}

std::vector<float> groupedLongestCurves(std::span<const ControlGrid> grids) {
    const std::vector<int> group = patchLodGroups(grids);
    std::vector<float> own(grids.size()), groupMax(grids.size(), 0.0f);
    for (size_t i = 0; i < grids.size(); ++i) {
        own[i] = longestCurve(grids[i]);
        groupMax[group[i]] = std::max(groupMax[group[i]], own[i]);
    }
    std::vector<float> result(grids.size());
    for (size_t i = 0; i < grids.size(); ++i) result[i] = groupMax[group[i]];
    return result;
}

}  // namespace q3::patch
