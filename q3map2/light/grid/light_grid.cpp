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

GridPlacement placeLightGrid(const LightContext& ctx) {
    const bsp::Entity* worldspawn = ctx.entities.empty() ? nullptr : &ctx.entities[0];
    const std::string gridSizeValue = worldspawn ? worldspawn->value("gridsize") : std::string();
    GridPlacement out;
    out.layout = computeGridLayout(
        parseGridSize(gridSizeValue, ctx.bspPath.string() + ": worldspawn \"gridsize\""), ctx.bsp);
    // Points are placed one after another in index order, as q3map2's TraceGrid places them on one
    // thread: a point in solid takes the first free one of its random nudges, whose values
    // continue the sequence light creation drew from (placeGridAsTraceGrid).
    const GridLayout& layout = out.layout;
    out.points = placeGridAsTraceGrid(ctx.tree.get(), GridLattice{layout.bounds, layout.mins, layout.size},
                                      ctx.random, ctx.threads);
    return out;
}

void lightGrid(LightContext& ctx, Log& log, const GridPlacement* placed) {
    bsp::Entity* worldspawn = ctx.entities.empty() ? nullptr : &ctx.entities[0];
    const GridPlacement own = placed ? GridPlacement{} : placeLightGrid(ctx);
    if (!placed) placed = &own;
    const GridLayout& layout = placed->layout;
    if (layout.growSteps > 0)
        log.info(strCat("grid size grown to ", layout.sizeKeyValue(), " to stay within ", kMaxGridPoints, " points"));

    const int numPoints = layout.numPoints();
    const GridOptions gridOptions = gridOptionsFromContext(ctx);
    const LightingEnv env = gridLightingEnv(ctx, layout.size);
    // The nudges reach half a cell along each axis at most.
    const float nudgeRadius = length(layout.size * 0.5f);
    const std::vector<std::optional<PlacedGridPoint>>& placements = placed->points;
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
    auto place = [&](size_t i) {
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
        auto lightPoint = [&](size_t i, Vec3, const BlockLights& reaching) {
            const std::optional<PlacedGridPoint> placed = place(i);
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
            thread_local std::vector<size_t> index;
            thread_local std::vector<Vec3> at;
            thread_local std::vector<int> clusters;
            thread_local std::vector<std::vector<LightContribution>> contributions;
            index.clear();
            at.clear();
            clusters.clear();
            for (const GridBlockPoint& p : blockPoints)
                if (const std::optional<PlacedGridPoint> placed = place(p.index)) {
                    index.push_back(p.index);
                    at.push_back(placed->origin);
                    clusters.push_back(placed->cluster);
                }
            contributions.resize(std::max(contributions.size(), index.size()));
            for (size_t k = 0; k < index.size(); ++k) contributions[k].clear();
            // Grid points sit on the map's lattice, often inside a wall's plane: rays along axial
            // planes keep the single-ray answer the grid has always had.
            traceBlockContributions(
                ctx.lights, reaching.candidates, reaching.clearOfSolid, envelopes, at, clusters, env, true, true,
                [](const Light&) { return true; },
                [&](size_t p, uint32_t, const LightContribution& c, const Vec3* transmission) {
                    if (transmission && c.color == Vec3{}) return;  // blocked, as an immediate trace leaves it out
                    contributions[p].push_back(c);
                });
            for (size_t k = 0; k < index.size(); ++k) store(index[k], contributions[k]);
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
