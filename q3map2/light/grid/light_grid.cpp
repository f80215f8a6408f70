// The legacy light grid (q3map2 SetupGrid / TraceGrid): layout from model 0 and worldspawn
// "gridsize", lit in parallel by blocks of points (lights culled once per block), in-solid points
// moved by q3map2's random nudges (drawn in its single-thread order), every occluder counted, and
// the lump-15 encoding of grid_encode.
#include <algorithm>

#include "grid_blocks.h"
#include "grid_encode.h"
#include "light_context.h"
#include "light_text.h"
#include "progress.h"

namespace q3::light {
namespace {

constexpr int kBlockEdge = 4;              // grid points per block edge (lights culled per block)

// One thread's working space for a block of the batched grid: where each point went, and per
// (light, point) its unoccluded contribution and the index of its shadow ray (-1: none).
struct GridBlockScratch {
    std::vector<std::optional<PlacedGridPoint>> placed;
    std::vector<std::optional<LightContribution>> pending;
    std::vector<int32_t> rayOf;
    std::vector<ShadowRay> rays;
    std::vector<Vec3> transmission;
    std::vector<LightContribution> contributions;
};

GridOptions gridOptionsFromContext(const LightContext& ctx) {
    GridOptions g;
    g.scale = ctx.options.gridScale;
    g.ambientScale = ctx.options.gridAmbientScale;
    g.directionality = ctx.options.gridDirectionality;
    g.ambientDirectionality = ctx.options.gridAmbientDirectionality;
    g.minLight = ctx.world.minGridLight;
    return g;
}

}  // namespace

void lightGrid(LightContext& ctx, Log& log) {
    bsp::Entity* worldspawn = ctx.entities.empty() ? nullptr : &ctx.entities[0];
    const std::string gridSizeValue = worldspawn ? worldspawn->value("gridsize") : std::string();
    const Vec3 requested = parseGridSize(gridSizeValue, ctx.bspPath.string() + ": worldspawn \"gridsize\"");
    const GridLayout layout = computeGridLayout(requested, ctx.bsp);
    if (layout.growSteps > 0)
        log.info(strCat("grid size grown to ", layout.sizeKeyValue(), " to stay within ", kMaxGridPoints, " points"));

    const int numPoints = layout.numPoints();
    const GridOptions gridOptions = gridOptionsFromContext(ctx);
    const LightingEnv env = gridLightingEnv(ctx, layout.size);
    // Points are placed first, one after another in index order, as q3map2's TraceGrid places them
    // on one thread: a point in solid takes the first free one of its random nudges, whose values
    // continue the sequence light creation drew from (placeGridAsTraceGrid). The nudges reach
    // half a cell along each axis at most.
    const float nudgeRadius = length(layout.size * 0.5f);
    const std::vector<std::optional<PlacedGridPoint>> placements = placeGridAsTraceGrid(
        ctx.tree.get(), ctx.bsp, GridLattice{layout.bounds, layout.mins, layout.size}, ctx.random, ctx.threads);
    const std::vector<float> envelopes = lightEnvelopes(ctx.lights, env.settings.forceFast);
    std::vector<bsp::GridPoint> points(static_cast<size_t>(std::max(0, numPoints)));
    std::vector<uint8_t> inSolid(points.size(), 0);
    log.info(strCat("light grid: ", layout.bounds[0], " x ", layout.bounds[1], " x ", layout.bounds[2], " = ",
                    numPoints, " points"));
    Progress progress = Progress::forConsole(log, points.size());
    // One grid point: nudged out of solid (or left all-zero, which the engine skips), then lit by
    // the lights that reach its block, in light order.
    LightingEnv clearEnv = env;
    clearEnv.clearOfSolid = true;
    auto place = [&](size_t i, Vec3) {
        const std::optional<PlacedGridPoint>& placed = placements[i];
        if (!placed) {
            points[i] = bsp::GridPoint{};
            inSolid[i] = 1;
        }
        return placed;
    };
    auto store = [&](size_t i, std::span<const LightContribution> contributions) {
        const GridSample sample = accumulateGridSample(contributions, ctx.world.ambient, gridOptions);
        points[i] = encodeGridPoint(sample, gridOptions, ctx.color);
    };
    // Nudged points move at most nudgeRadius from their lattice position.
    const GridLattice lattice{layout.bounds, layout.mins, layout.size};
    const float margin = nudgeRadius + 1.0f;
    if (ctx.options.cheapGrid || !env.scene) {
        // Point by point, each ray traced at once: -cheapgrid stops at the first light that saturates.
        auto lightPoint = [&](size_t i, Vec3 latticePoint, const BlockLights& reaching) {
            const std::optional<PlacedGridPoint> placed = place(i, latticePoint);
            if (!placed) return;
            thread_local std::vector<LightContribution> contributions;
            contributions.clear();
            Vec3 total = ctx.world.ambient;
            for (size_t k = 0; k < reaching.candidates.size(); ++k) {
                const uint32_t lightIndex = reaching.candidates[k];
                const bool clear = !reaching.clearOfSolid.empty() && reaching.clearOfSolid[k];
                std::optional<LightContribution> c = lightToGridPoint(ctx.lights[lightIndex], placed->origin,
                                                                      placed->cluster, clear ? clearEnv : env,
                                                                      envelopes[lightIndex]);
                if (!c) continue;
                contributions.push_back(*c);
                total += c->color;
                if (ctx.options.cheapGrid && total.x >= 255 && total.y >= 255 && total.z >= 255) break;
            }
            store(i, contributions);
        };
        lightGridByBlocks(lattice, ctx.lights, margin, env.settings, kBlockEdge, ctx.threads, progress, lightPoint,
                          ctx.tree.get());
    } else {
        // Block by block: every light's rays from all the block's points are traced together (one
        // origin, nearby ends: coherent batches), then each point adds its lights up in light order,
        // as the point-by-point form does.
        auto lightBlock = [&](std::span<const GridBlockPoint> blockPoints, const BlockLights& reaching) {
            thread_local GridBlockScratch s;
            const size_t np = blockPoints.size(), nl = reaching.candidates.size();
            s.placed.resize(np);
            for (size_t p = 0; p < np; ++p) s.placed[p] = place(blockPoints[p].index, blockPoints[p].origin);
            s.pending.assign(nl * np, std::nullopt);
            s.rayOf.assign(nl * np, -1);
            s.rays.clear();
            LightingEnv deferred = env, deferredClear = clearEnv;
            deferred.deferredRays = deferredClear.deferredRays = &s.rays;
            for (size_t k = 0; k < nl; ++k) {
                const uint32_t lightIndex = reaching.candidates[k];
                const bool clear = !reaching.clearOfSolid.empty() && reaching.clearOfSolid[k];
                for (size_t p = 0; p < np; ++p) {
                    if (!s.placed[p]) continue;
                    const size_t before = s.rays.size();
                    std::optional<LightContribution> c = lightToGridPoint(ctx.lights[lightIndex], s.placed[p]->origin,
                                                                          s.placed[p]->cluster,
                                                                          clear ? deferredClear : deferred,
                                                                          envelopes[lightIndex]);
                    if (!c) {
                        s.rays.resize(before);
                        continue;
                    }
                    s.pending[k * np + p] = c;
                    if (s.rays.size() > before) s.rayOf[k * np + p] = int32_t(before);
                }
            }
            s.transmission.resize(s.rays.size());
            // Grid points sit on the map's lattice, often inside a wall's plane: rays along axial
            // planes keep the single-ray answer the grid has always had.
            if (!s.rays.empty()) env.scene->traceBatch(s.rays, s.transmission, true, true);
            for (size_t p = 0; p < np; ++p) {
                if (!s.placed[p]) continue;
                s.contributions.clear();
                for (size_t k = 0; k < nl; ++k) {
                    std::optional<LightContribution>& c = s.pending[k * np + p];
                    if (!c) continue;
                    if (const int32_t ray = s.rayOf[k * np + p]; ray >= 0) {
                        c->color *= s.transmission[size_t(ray)];
                        if (c->color == Vec3{}) continue;  // blocked, as an immediate trace leaves it out
                    }
                    s.contributions.push_back(*c);
                }
                store(blockPoints[p].index, s.contributions);
            }
        };
        lightGridBlocks(lattice, ctx.lights, margin, env.settings, kBlockEdge, ctx.threads, progress, lightBlock,
                        ctx.tree.get());
    }
    progress.finish();

    ctx.bsp.lightGrid = std::move(points);
    ctx.stats.gridPoints = static_cast<uint64_t>(std::max(0, numPoints));
    for (uint8_t s : inSolid) ctx.stats.gridPointsInSolid += s;
    if (layout.sizeChanged() && worldspawn) worldspawn->set("gridsize", layout.sizeKeyValue());
    log.info(strCat(ctx.stats.gridPointsInSolid, " grid points in solid"));
}

}  // namespace q3::light
