#include "grid_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>

namespace q3::info {

LegacyGridLayout legacyGridLayout(const float worldMins[3], const float worldMaxs[3], const float cellSize[3]) {
    LegacyGridLayout layout;
    layout.points = 1;
    for (int i = 0; i < 3; ++i) {
        float size = cellSize[i];
        layout.cellSize[i] = size;
        layout.origin[i] = size * std::ceil(worldMins[i] / size);
        float maxs = size * std::floor(worldMaxs[i] / size);
        // Engines truncate toward zero when storing the count in an int.
        layout.bounds[i] = static_cast<int32_t>((maxs - layout.origin[i]) / size + 1);
        layout.points *= std::max<int32_t>(0, layout.bounds[i]);
    }
    return layout;
}

void parseGridSize(std::string_view value, float cellSize[3]) {
    std::istringstream in{std::string(value)};
    for (int i = 0; i < 3; ++i) {
        float v = 0;
        if (!(in >> v)) return;
        if (std::isfinite(v) && v > 0) cellSize[i] = v;
    }
}

ShGridStats shGridStats(const sh::GridSH& grid) {
    ShGridStats stats;
    stats.points = static_cast<int64_t>(grid.points.size());
    if (grid.points.empty()) return stats;
    stats.coeff0Min = std::numeric_limits<float>::max();
    stats.coeff0Max = std::numeric_limits<float>::lowest();
    double sum = 0;
    for (const sh::GridPointSH& p : grid.points) {
        for (int c = 0; c < 3; ++c) {
            float v = p.coeffs[0][c];
            stats.coeff0Min = std::min(stats.coeff0Min, v);
            stats.coeff0Max = std::max(stats.coeff0Max, v);
            sum += v;
        }
        bool zero = true;
        for (const auto& coefficient : p.coeffs)
            for (float v : coefficient) zero = zero && v == 0.0f;
        if (zero) ++stats.allZeroPoints;
    }
    stats.coeff0Mean = sum / (3.0 * static_cast<double>(grid.points.size()));
    return stats;
}

}  // namespace q3::info
