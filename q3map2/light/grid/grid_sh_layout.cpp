// SH grid layout (SetupGridSH) and storage of the finished grid in a BSP; see grid_sh.h.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "grid_encode.h"
#include "grid_sh.h"
#include "light_context.h"
#include "light_text.h"
#include "log.h"

namespace q3::light {
namespace {

// Same guard as the legacy grid: no engine goes near these coordinates, and it keeps the point
// counts of broken bounds finite.
constexpr double kWorldLimit = 1048576.0;

double clampCoordinate(float v) {
    if (!std::isfinite(v)) return 0.0;
    return std::clamp(static_cast<double>(v), -kWorldLimit, kWorldLimit);
}

void placeGrid(ShGridLayout& layout, Vec3 worldMins, Vec3 worldMaxs) {
    for (int axis = 0; axis < 3; ++axis) {
        const double s = layout.size[axis];
        const double lo = s * std::ceil(clampCoordinate(worldMins[axis]) / s);
        const double hi = s * std::floor(clampCoordinate(worldMaxs[axis]) / s);
        const long long count = std::llround((hi - lo) / s) + 1;
        layout.mins[axis] = static_cast<float>(lo);
        layout.bounds[axis] = static_cast<int>(std::max(1LL, count));
    }
}

std::string formatSize(Vec3 size) {
    char text[128];
    std::snprintf(text, sizeof(text), "%g %g %g", size.x, size.y, size.z);
    return text;
}

}  // namespace

ShGridLayout computeShGridLayout(Vec3 requestedSize, Vec3 worldMins, Vec3 worldMaxs, uint64_t maxLumpBytes) {
    ShGridLayout layout;
    layout.requestedSize = requestedSize;
    layout.size = requestedSize;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(layout.size[axis] >= kMinShCellSize)) {  // also catches NaN
            layout.size[axis] = kMinShCellSize;
            layout.clamped = true;
        }
    }
    placeGrid(layout, worldMins, worldMaxs);
    while (layout.lumpBytes() > maxLumpBytes) {
        layout.size += Vec3::splat(kMinShCellSize);
        ++layout.growSteps;
        placeGrid(layout, worldMins, worldMaxs);
    }
    return layout;
}

Vec3 requestedShCellSize(const LightContext& ctx) {
    const float* explicitSize = ctx.options.gridSizeSH;
    if (explicitSize[0] > 0 && explicitSize[1] > 0 && explicitSize[2] > 0)
        return {explicitSize[0], explicitSize[1], explicitSize[2]};
    const std::string gridSizeValue = ctx.entities.empty() ? std::string() : ctx.entities[0].value("gridsize");
    const Vec3 legacy = parseGridSize(gridSizeValue, ctx.bspPath.string() + ": worldspawn \"gridsize\"");
    const float scale = ctx.options.gridScaleSH;
    if (!(scale > 0) || !std::isfinite(scale))
        throw CompileError(ctx.bspPath.string() + ": -gridscalesh must be a positive number");
    return legacy / scale;
}

ShGridLayout setupGridSH(const LightContext& ctx, Log& log) {
    const Vec3 requested = requestedShCellSize(ctx);
    Vec3 worldMins, worldMaxs;
    if (!ctx.bsp.models.empty()) {
        worldMins = Vec3::fromArray(ctx.bsp.models[0].mins);
        worldMaxs = Vec3::fromArray(ctx.bsp.models[0].maxs);
    }
    const ShGridLayout layout = computeShGridLayout(requested, worldMins, worldMaxs);
    if (layout.clamped)
        log.warning(strCat("SH grid cell size ", formatSize(requested), " raised to ",
                           formatSize(vmax(requested, Vec3::splat(kMinShCellSize))), " (each axis at least ",
                           kMinShCellSize, " units)"));
    if (layout.growSteps > 0)
        log.warning(strCat("SH grid cell size grown to ", formatSize(layout.size), " to keep lump 18 within ",
                           kMaxShLumpBytes >> 20, " MiB (",
                           layout.numPoints(), " points)"));
    log.info(strCat("SH grid: cell ", formatSize(layout.size), ", ", layout.bounds[0], " x ", layout.bounds[1], " x ",
                    layout.bounds[2], " = ", layout.numPoints(), " points, ", layout.lumpBytes(), " bytes"));
    return layout;
}

void attachGridSH(bsp::Bsp& bsp, sh::GridLumpImage&& grid, bool bspx) {
    std::vector<uint8_t> image = grid.release();
    if (bspx) {
        bsp::detachShGrid(bsp);
        bsp.setBspx(sh::kBspxLumpName, std::move(image));
    } else {
        bsp.removeBspx(sh::kBspxLumpName);
        bsp::attachShGrid(bsp, std::move(image));
    }
}

void removeGridSH(bsp::Bsp& bsp) {
    if (!bsp.shGrid.empty()) bsp::detachShGrid(bsp);
    bsp.removeBspx(sh::kBspxLumpName);
}

}  // namespace q3::light
