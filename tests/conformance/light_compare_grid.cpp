// The legacy light grid figures: totals, correlations and directions, with and without the mask
// of points on which two reference runs agree.
#include <cmath>
#include <cstdlib>
#include <limits>

#include "light_compare.h"

namespace q3::conformance {
namespace {

constexpr int kAgreeBytes = 2;
constexpr int kDirectedForDirection = 30;
constexpr double kDirectionDegrees = 15;

int sum3(const uint8_t* v) { return int(v[0]) + v[1] + v[2]; }

GridStats gridStats(const std::vector<bsp::GridPoint>& reference, const std::vector<bsp::GridPoint>& ours,
                    const std::vector<bool>* mask) {
    GridStats g;
    double refAmbient = 0, ourAmbient = 0, refDirected = 0, ourDirected = 0;
    std::vector<double> ra, oa, rd, od;
    int aligned = 0;
    const double cosLimit = std::cos(kDirectionDegrees * kPiD / 180);
    for (size_t i = 0; i < reference.size(); ++i) {
        if (mask && !(*mask)[i]) continue;
        const bsp::GridPoint& r = reference[i];
        const bsp::GridPoint& o = ours[i];
        ++g.points;
        refAmbient += sum3(r.ambient);
        ourAmbient += sum3(o.ambient);
        refDirected += sum3(r.directed);
        ourDirected += sum3(o.directed);
        ra.push_back(sum3(r.ambient));
        oa.push_back(sum3(o.ambient));
        rd.push_back(sum3(r.directed));
        od.push_back(sum3(o.directed));
        if (sum3(r.directed) >= kDirectedForDirection) {
            ++g.directionPoints;
            if (double(dot(gridDirection(r), gridDirection(o))) >= cosLimit) ++aligned;
        }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    g.ambientRatio = refAmbient > 0 ? ourAmbient / refAmbient : nan;
    g.directedRatio = refDirected > 0 ? ourDirected / refDirected : nan;
    g.ambientCorrelation = pearson(ra, oa);
    g.directedCorrelation = pearson(rd, od);
    g.directionFraction = g.directionPoints ? double(aligned) / g.directionPoints : nan;
    return g;
}

}  // namespace

Vec3 gridDirection(const bsp::GridPoint& point) {
    // ioquake3: byte 7 is the azimuth ("lat"), byte 6 the angle from +z ("lng"), 256 steps a turn.
    const double step = 2 * kPiD / 256;
    const double lat = point.latLong[1] * step;
    const double lng = point.latLong[0] * step;
    return {float(std::cos(lat) * std::sin(lng)), float(std::sin(lat) * std::sin(lng)), float(std::cos(lng))};
}

bool gridPointPlaced(const bsp::GridPoint& point) {
    const uint8_t* bytes = reinterpret_cast<const uint8_t*>(&point);
    for (size_t i = 0; i < sizeof(point); ++i)
        if (bytes[i] != 0) return true;
    return false;
}

bool gridPointsAgree(const bsp::GridPoint& a, const bsp::GridPoint& b) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(a.ambient[c]) - int(b.ambient[c])) > kAgreeBytes ||
            std::abs(int(a.directed[c]) - int(b.directed[c])) > kAgreeBytes)
            return false;
    return true;
}

GridFigures compareGrids(const std::vector<bsp::GridPoint>& reference, const std::vector<bsp::GridPoint>& ours,
                         const std::vector<bsp::GridPoint>* reference2) {
    GridFigures f;
    f.referencePoints = int(reference.size());
    f.oursPoints = int(ours.size());
    f.countsMatch = reference.size() == ours.size();
    if (!f.countsMatch) return f;
    f.all = gridStats(reference, ours, nullptr);
    f.masked = reference2 && reference2->size() == reference.size();
    if (!f.masked) return f;
    std::vector<bool> mask(reference.size());
    for (size_t i = 0; i < reference.size(); ++i)
        mask[i] = gridPointsAgree(reference[i], (*reference2)[i]) && gridPointPlaced(reference[i]) &&
                  gridPointPlaced((*reference2)[i]);
    f.agreed = gridStats(reference, ours, &mask);
    return f;
}

}  // namespace q3::conformance
