// q3map2's measure of how curved a patch is, and the subdivision level it picks from it.
#include <algorithm>
#include <cmath>

#include "patch.h"

namespace q3::patch {
namespace {

// Length estimate of the quadratic span a-b-c, or 0 when the span is straight or has a very short
// leg. q3map2 walks 8 steps of the point a + (1-t)(b-a) + t(c-b), t = 0, 1/8 .. 7/8: the first step
// goes from a to b, the other seven each add |(c-b)-(b-a)|/8. The sum is written out directly.
double spanCurveLength(Vec3 a, Vec3 b, Vec3 c) {
    constexpr float kMinLeg = 0.125f;
    constexpr float kStraight = 0.99f;
    const Vec3 ab = b - a, bc = c - b, ac = c - a;
    if (length(ab) < kMinLeg || length(bc) < kMinLeg || length(ac) < kMinLeg) return 0;
    const Vec3 abDir = normalize(ab), bcDir = normalize(bc), acDir = normalize(ac);
    if (dot(abDir, bcDir) > kStraight && dot(abDir, acDir) > kStraight) return 0;
    return double(length(ab)) + 7.0 / 8.0 * double(length(bc - ab));
}

}  // namespace

float longestCurve(const ControlGrid& grid) {
    if (!isValidGrid(grid)) return 0;
    double longest = 0;
    // As in q3map2, each 3x3 sub-patch contributes the span along its first row and the span down
    // its first column (the grid's last row and last column are not measured).
    for (int column = 0; column + 2 < grid.width; column += 2) {
        for (int row = 0; row + 2 < grid.height; row += 2) {
            const Vec3 corner = grid.at(column, row).xyz;
            longest = std::max(longest, spanCurveLength(corner, grid.at(column + 1, row).xyz, grid.at(column + 2, row).xyz));
            longest = std::max(longest, spanCurveLength(corner, grid.at(column, row + 1).xyz, grid.at(column, row + 2).xyz));
        }
    }
    return float(longest);
}

int iterationsForCurve(float curveLength, int subdivisions) {
    if (subdivisions < 1) subdivisions = 1;
    int iterations = 0;
    for (; iterations < kMaxIterations; ++iterations) {
        const double facets = double(subdivisions) * 16.0 * double(1 << iterations);
        if (facets >= curveLength) break;
    }
    return iterations;
}

int segmentsPerSpan(int iterations) {
    return 2 << std::clamp(iterations, 0, kMaxIterations);
}

}  // namespace q3::patch
