// The tests' plain reference for q3map2's smoothing groups (phong.h hashes positions instead).
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "vec3.h"

namespace q3::light {

// One group: vertex i and every ungrouped vertex j >= i of `candidates` (ascending) at the same
// position (0.001 per axis) whose normal is within the smaller of the two angles (radians, 0 = not
// smoothed), at most 256. The group's normal, kept for two members or more, is the normalized sum
// of its distinct normals (0.01 per axis); members are marked in `grouped`.
inline void referenceSmoothGroup(size_t i, std::span<const size_t> candidates, const std::vector<Vec3>& p,
                            const std::vector<Vec3>& n, const std::vector<float>& radians,
                            std::vector<bool>& grouped, std::vector<Vec3>& out) {
    std::vector<size_t> members;
    std::vector<Vec3> votes;
    Vec3 sum{};
    for (size_t j : candidates) {
        if (j < i || grouped[j] || members.size() >= 256 || radians[j] <= 0) continue;
        const Vec3 d = p[i] - p[j];
        if (!(std::fabs(d.x) < 0.001f && std::fabs(d.y) < 0.001f && std::fabs(d.z) < 0.001f)) continue;
        const double c = std::clamp(double(n[i].x) * n[j].x + double(n[i].y) * n[j].y + double(n[i].z) * n[j].z, -1.0, 1.0);
        if (std::acos(c) + 0.000001 >= std::min(radians[i], radians[j])) continue;
        members.push_back(j);
        grouped[j] = true;
        const bool voted = std::any_of(votes.begin(), votes.end(), [&](Vec3 w) {
            return std::fabs(w.x - n[j].x) < 0.01f && std::fabs(w.y - n[j].y) < 0.01f && std::fabs(w.z - n[j].z) < 0.01f;
        });
        if (!voted) {
            votes.push_back(n[j]);
            sum += n[j];
        }
    }
    if (members.size() < 2 || normalize(sum) == Vec3{}) return;
    for (size_t j : members) out[j] = normalize(sum);
}

}  // namespace q3::light
