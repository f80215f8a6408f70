#include "meta_smooth.h"

#include <algorithm>
#include <cmath>

#include "shader_info.h"

namespace q3::bspstage::meta {
namespace {

constexpr double kThetaEpsilon = 0.000001;
constexpr float kEqualNormalEpsilon = 0.01f;

float radians(float degrees) { return degrees * float(3.14159265358979323846 / 180.0); }

// One triangle corner at the group's position.
struct Corner {
    int vertex;
    int triangle;
    float angle = 0;  // radians
    bool skipped = false;
    bool smoothed = false;
    Vec3 normal{0, 0, 0};
};

bool withinEpsilon(const Vec3& a, const Vec3& b, float epsilon) {
    return std::fabs(a.x - b.x) < epsilon && std::fabs(a.y - b.y) < epsilon && std::fabs(a.z - b.z) < epsilon;
}

// Smooths the corners of one group; returns the number of corner sets smoothed.
int smoothGroup(MetaTriangles& set, int group, float defaultAngle) {
    std::vector<Corner> corners;
    for (int v : set.groups[size_t(group)])
        for (int t : set.vertices[size_t(v)].triangles) corners.push_back({v, t});
    float maxAngle = 0;
    for (Corner& c : corners) {
        const MetaTriangle& t = set.triangles[size_t(c.triangle)];
        float angle = defaultAngle;
        if (t.shader->shadeAngleDegrees > 0)
            angle = radians(t.shader->shadeAngleDegrees);
        else if (t.shadeAngle > 0)
            angle = radians(t.shadeAngle);
        c.angle = angle;
        c.skipped = angle <= 0;
        maxAngle = std::max(maxAngle, angle);
    }
    if (maxAngle <= 0) return 0;

    int smoothedSets = 0;
    for (size_t i = 0; i < corners.size(); ++i) {
        if (corners[i].skipped || corners[i].smoothed) continue;
        const Vec3 n1 = normalOf(set.vertices[size_t(corners[i].vertex)].vert);
        Vec3 sum{0, 0, 0};
        std::vector<size_t> members;
        std::vector<Vec3> votes;
        for (size_t j = i; j < corners.size(); ++j) {
            if (corners[j].skipped || corners[j].smoothed) continue;
            const float angle = std::min(corners[i].angle, corners[j].angle);
            const Vec3 n2 = normalOf(set.vertices[size_t(corners[j].vertex)].vert);
            const double d = std::clamp(double(dot(n1, n2)), -1.0, 1.0);
            if (std::acos(d) + kThetaEpsilon >= angle) continue;
            members.push_back(j);
            if (std::none_of(votes.begin(), votes.end(), [&](const Vec3& v) { return withinEpsilon(n2, v, kEqualNormalEpsilon); })) {
                sum += n2;
                votes.push_back(n2);
            }
        }
        // The sum is normalised in double precision, as q3map2's VectorNormalize does.
        const DVec3 total(sum);
        const double len = length(total);
        if (members.size() > 1 && len != 0) {
            const Vec3 average = (total / len).toFloat();
            for (size_t m : members) {
                corners[m].smoothed = true;
                corners[m].normal = average;
            }
            ++smoothedSets;
        } else {
            for (size_t m : members) corners[m].skipped = true;
        }
    }
    if (std::none_of(corners.begin(), corners.end(), [](const Corner& c) { return c.smoothed; })) return smoothedSets;

    // Rebuild the group's vertices from the corners: equal ones are shared again.
    std::vector<int> rebuilt;
    for (const Corner& c : corners) {
        bsp::DrawVert v = set.vertices[size_t(c.vertex)].vert;
        if (c.smoothed) c.normal.toArray(v.normal);
        int target = -1;
        for (int r : rebuilt)
            if (sameVertex(v, set.vertices[size_t(r)].vert)) {
                target = r;
                break;
            }
        if (target < 0) {
            target = int(set.vertices.size());
            set.vertices.push_back({v, group, {}});
            rebuilt.push_back(target);
        }
        set.vertices[size_t(target)].triangles.push_back(c.triangle);
        std::array<int, 3>& tv = set.triangles[size_t(c.triangle)].verts;
        *std::find(tv.begin(), tv.end(), c.vertex) = target;
    }
    for (int old : set.groups[size_t(group)]) set.vertices[size_t(old)].triangles.clear();
    set.groups[size_t(group)] = std::move(rebuilt);
    return smoothedSets;
}

}  // namespace

int smoothMetaTriangles(MetaTriangles& set, float npDegrees) {
    const float defaultAngle = radians(npDegrees);
    int smoothed = 0;
    for (size_t g = 0; g < set.groups.size(); ++g) {
        const std::vector<int>& group = set.groups[g];
        if (group.size() > 1 || (group.size() == 1 && set.vertices[size_t(group.front())].triangles.size() > 1))
            smoothed += smoothGroup(set, int(g), defaultAngle);
    }
    return smoothed;
}

}  // namespace q3::bspstage::meta
