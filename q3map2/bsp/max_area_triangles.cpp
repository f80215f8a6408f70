#include "max_area_triangles.h"

#include <cmath>
#include <vector>

namespace q3::bspstage {
namespace {

constexpr double kTinyArea = 1.0;  // twice the area below which a triangle is a sliver
constexpr int kMaxTries = 8;

struct MaxAreaSplitter {
    const DrawSurface& ds;
    LibcRandom& random;

    Vec3 at(int vertex) const { return xyzOf(ds.verts[size_t(vertex)]); }

    // How much to shorten each side of a candidate triangle: about 8 pixels of a polygon filling a
    // quarter of a 1280 wide screen, less for small polygons so that some triangle still scores.
    double penaltyWidth(const std::vector<int>& polygon) const {
        const int n = int(polygon.size());
        double area = 0, perimeter = 0;
        for (int i = 1; i + 1 < n; ++i) area += triangleArea2x(at(polygon[0]), at(polygon[size_t(i)]), at(polygon[size_t(i + 1)]));
        for (int i = 0; i < n; ++i) perimeter += length(at(polygon[size_t((i + 1) % n)]) - at(polygon[size_t(i)]));
        const double depth = std::ceil(std::log(n / 1.5) / std::log(2.0));
        double width = std::sqrt(area) * 0.0125;
        if (area - depth * perimeter * width * 2 < 0) width = area / (depth * perimeter * 2);
        return width;
    }

    // Appends the triangles of the polygon (vertex numbers of the surface, in winding order) to
    // `out`; false when every attempt ran into a sliver.
    bool split(const std::vector<int>& polygon, std::vector<int>& out) {
        const int n = int(polygon.size());
        if (n < 3) return true;
        const double width = penaltyWidth(polygon);
        int bestR = 0, bestS = 1, bestT = 2;
        double bestArea = -1, bestValue = -1;
        for (int r = 0; r + 2 < n; ++r)
            for (int s = r + 1; s + 1 < n; ++s)
                for (int t = s + 1; t < n; ++t) {
                    const Vec3 ab = at(polygon[size_t(s)]) - at(polygon[size_t(r)]);
                    const Vec3 ac = at(polygon[size_t(t)]) - at(polygon[size_t(r)]);
                    const Vec3 bc = at(polygon[size_t(t)]) - at(polygon[size_t(s)]);
                    const double area = length(cross(ab, ac));
                    // q3map2's sign mix of the three sides, kept: it decides which triangle wins.
                    const float sides = length(ab) - length(ac) - length(bc);
                    const double value = area - double(sides) * width;
                    if (bestArea < 0 || value > bestValue) {
                        bestArea = area;
                        bestValue = value;
                        bestR = r;
                        bestS = s;
                        bestT = t;
                    }
                }
        const size_t start = out.size();
        for (int attempt = 0; attempt < kMaxTries; ++attempt) {
            out.resize(start);
            if (attempt > 0) {
                bestR = random.next() % n;
                bestS = random.next() % n;
                bestT = random.next() % n;
                if (bestR == bestS || bestR == bestT || bestS == bestT) continue;
                if (bestR > bestS) std::swap(bestR, bestS);
                if (bestS > bestT) std::swap(bestS, bestT);
                if (bestR > bestS) std::swap(bestR, bestS);
                bestArea = triangleArea2x(at(polygon[size_t(bestR)]), at(polygon[size_t(bestS)]), at(polygon[size_t(bestT)]));
            }
            if (bestArea < kTinyArea) continue;
            out.insert(out.end(), {polygon[size_t(bestR)], polygon[size_t(bestS)], polygon[size_t(bestT)]});
            // The polygon without the triangle: the runs R..S, S..T and T..R (wrapping).
            const std::vector<int> first(polygon.begin() + bestR, polygon.begin() + bestS + 1);
            if (!split(first, out)) continue;
            const std::vector<int> second(polygon.begin() + bestS, polygon.begin() + bestT + 1);
            if (!split(second, out)) continue;
            std::vector<int> third(polygon.begin() + bestT, polygon.end());
            third.insert(third.end(), polygon.begin(), polygon.begin() + bestR + 1);
            if (!split(third, out)) continue;
            return true;
        }
        out.resize(start);
        return false;
    }
};

}  // namespace

void triangulateFaceByMaxArea(DrawSurface& ds, LibcRandom& random, TriangulationCounts* counts) {
    const int n = int(ds.verts.size());
    if (n == 0) return;
    if (n == 3) {
        ds.indexes = {0, 1, 2};
        if (counts) ++counts->maxArea;
        return;
    }
    std::vector<int> polygon(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) polygon[size_t(i)] = i;
    std::vector<int> indexes;
    MaxAreaSplitter splitter{ds, random};
    if (!splitter.split(polygon, indexes)) {
        triangulateFace(ds, counts);  // degenerate whatever the order: strip or fan
        return;
    }
    ds.indexes = std::move(indexes);
    if (counts) ++counts->maxArea;
}

}  // namespace q3::bspstage
