// Block decomposition of light grids (see grid_blocks.h).
#include "grid_blocks.h"

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "bsp_tree.h"
#include "progress.h"
#include "trace_scene.h"

namespace q3::light {

std::vector<GridBlock> gridBlocks(std::array<int, 3> bounds, int edge) {
    std::vector<GridBlock> blocks;
    edge = std::max(1, edge);
    if (bounds[0] <= 0 || bounds[1] <= 0 || bounds[2] <= 0) return blocks;
    for (int z = 0; z < bounds[2]; z += edge)
        for (int y = 0; y < bounds[1]; y += edge)
            for (int x = 0; x < bounds[0]; x += edge) {
                GridBlock b;
                b.first = {x, y, z};
                b.end = {std::min(x + edge, bounds[0]), std::min(y + edge, bounds[1]), std::min(z + edge, bounds[2])};
                blocks.push_back(b);
            }
    return blocks;
}

Bounds gridBlockBounds(const GridBlock& block, Vec3 mins, Vec3 size, float margin) {
    Bounds b;
    for (int axis = 0; axis < 3; ++axis) {
        b.mins[axis] = mins[axis] + float(block.first[axis]) * size[axis] - margin;
        b.maxs[axis] = mins[axis] + float(block.end[axis] - 1) * size[axis] + margin;
    }
    return b;
}

void gridLightsReaching(std::span<const Light> lights, std::span<const float> envelopes, const Bounds& bounds,
                        const ContributionSettings& settings, std::vector<uint32_t>& out) {
    gridLightsReaching(lights, LightReach(lights, envelopes), bounds, settings, out);
}

void gridLightsReaching(std::span<const Light> lights, const LightReach& reach, const Bounds& bounds,
                        const ContributionSettings& settings, std::vector<uint32_t>& out) {
    reach.reaching(bounds, out);
    std::erase_if(out, [&](uint32_t i) { return !mayLightGridIn(lights[i], bounds, settings); });
}

bool mayLightGridIn(const Light& light, const Bounds& bounds, const ContributionSettings& settings) {
    return light.affectsGrid && !areaLightSurelyDarkIn(light, bounds, settings);
}

namespace {
constexpr float kGridEpsilon = 0.0f;       // GRID_EPSILON: first point-in-solid test
constexpr float kNudgedEpsilon = -0.125f;  // VERTEX_EPSILON: test of nudged points
}  // namespace

std::optional<PlacedGridPoint> placeGridPoint(const BspTree* tree, Vec3 origin, const GridNudges& nudges) {
    if (!tree || !tree->hasNodes()) return PlacedGridPoint{origin, -1, false};
    const int cluster = tree->clusterForPointExt(origin, kGridEpsilon);
    if (cluster >= 0) return PlacedGridPoint{origin, cluster, false};
    const std::optional<Vec3> free = tree->nudgeOutOfSolid(origin, nudges.offsets, nudges.box, kNudgedEpsilon);
    if (!free) return std::nullopt;
    return PlacedGridPoint{*free, tree->clusterForPoint(*free), true};
}

namespace {

// q3map2's nudge step of try k: 0.005 added k + 1 times, in double.
const std::array<double, kGridNudgeTries>& gridNudgeSteps() {
    static const std::array<double, kGridNudgeTries> steps = [] {
        std::array<double, kGridNudgeTries> out{};
        double step = 0.0;
        for (double& s : out) s = step += 0.005;
        return out;
    }();
    return steps;
}

}  // namespace

int firstGridNudgeThatMayLeaveSolid(const BspTree& tree, Vec3 origin, Vec3 cellSize) {
    const std::array<double, kGridNudgeTries>& steps = gridNudgeSteps();
    // Try k moves each coordinate by at most half of step k times the cell (then rounds to float,
    // which the 0.01 covers): its box holds every earlier try too, the steps growing.
    auto triesUpToStaySolid = [&](int k) {
        const double reach = 0.5 * steps[size_t(k)];
        const Vec3 half{float(reach * cellSize.x + 0.01), float(reach * cellSize.y + 0.01),
                        float(reach * cellSize.z + 0.01)};
        return tree.boxInSolid(origin - half, origin + half, kNudgedEpsilon);
    };
    if (triesUpToStaySolid(kGridNudgeTries - 1)) return kGridNudgeTries;
    // The first k whose box is not known to stay solid (every try before it fails): lo stays
    // solid (or is -1), hi does not.
    int lo = -1, hi = kGridNudgeTries - 1;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        (triesUpToStaySolid(mid) ? lo : hi) = mid;
    }
    return hi;
}

std::optional<PlacedGridPoint> nudgeGridPointAsTraceGrid(const BspTree& tree, Vec3 origin, Vec3 cellSize,
                                                         CLibraryRandom& random, int firstTry) {
    const std::array<double, kGridNudgeTries>& steps = gridNudgeSteps();
    // The tries from `firstTry` on as q3map2 computes them (in double, rounded to float), a few at
    // a time: most points get out within a few tries of the first that can, and only the tries up
    // to the first free one consume values.
    constexpr int kTriesAtOnce = 16;
    thread_local std::vector<Vec3> tries;
    firstTry = std::clamp(firstTry, 0, kGridNudgeTries);
    CLibraryRandom drawn = random;
    drawn.discard(3 * uint64_t(firstTry));
    auto moved = [&](float base, double step, float size) {
        const double unit = double(drawn.unit());
        return float(double(base) + (unit - 0.5) * step * double(size));
    };
    for (int k = firstTry; k < kGridNudgeTries; k += kTriesAtOnce) {
        const CLibraryRandom before = drawn;
        tries.clear();
        for (int j = k; j < std::min(k + kTriesAtOnce, kGridNudgeTries); ++j) {
            const float x = moved(origin.x, steps[size_t(j)], cellSize.x);
            const float y = moved(origin.y, steps[size_t(j)], cellSize.y);
            const float z = moved(origin.z, steps[size_t(j)], cellSize.z);
            tries.push_back(Vec3{x, y, z});
        }
        // The tries are whole positions: added to the world's origin, they stay exact.
        const std::optional<Vec3> free = tree.nudgeOutOfSolid(Vec3{}, tries, kNudgedEpsilon);
        if (!free) continue;
        const auto first = std::find(tries.begin(), tries.end(), *free);
        random = before;
        random.discard(3 * (uint64_t(first - tries.begin()) + 1));
        return PlacedGridPoint{*free, tree.clusterForPoint(*free), true};
    }
    random = drawn;
    return std::nullopt;
}

std::vector<std::optional<PlacedGridPoint>> placeGridAsTraceGrid(const BspTree* tree, const GridLattice& grid,
                                                                 CLibraryRandom random, int threads) {
    const size_t bx = size_t(std::max(0, grid.bounds[0])), by = size_t(std::max(0, grid.bounds[1]));
    const size_t count = bx * by * size_t(std::max(0, grid.bounds[2]));
    auto latticePoint = [&](size_t i) {
        const size_t x = i % bx, y = (i / bx) % by, z = i / (bx * by);
        return Vec3{grid.mins.x + float(x) * grid.size.x, grid.mins.y + float(y) * grid.size.y,
                    grid.mins.z + float(z) * grid.size.z};
    };
    std::vector<std::optional<PlacedGridPoint>> placements(count);
    // In parallel, what needs no draw: free lattice points, and for the others the first try that
    // may be free (kGridNudgeTries: none).
    std::vector<uint8_t> firstTry(count, 0);
    static_assert(kGridNudgeTries <= 255, "firstTry holds a try index or kGridNudgeTries");
    const GridNudges noNudges{std::vector<Vec3>{}};
    tbb::task_arena(threads > 0 ? threads : tbb::task_arena::automatic).execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i) {
                placements[i] = placeGridPoint(tree, latticePoint(i), noNudges);
                if (!placements[i])
                    firstTry[i] = uint8_t(firstGridNudgeThatMayLeaveSolid(*tree, latticePoint(i), grid.size));
            }
        });
    });
    uint64_t skipped = 0;  // values drawn by the hopeless points since the last search
    for (size_t i = 0; i < count; ++i) {
        if (placements[i]) continue;
        if (firstTry[i] == kGridNudgeTries) {
            skipped += 3 * kGridNudgeTries;
            continue;
        }
        random.discard(skipped);
        skipped = 0;
        placements[i] = nudgeGridPointAsTraceGrid(*tree, latticePoint(i), grid.size, random, firstTry[i]);
    }
    return placements;
}

bool gridBoxToPointClear(const BspTree& tree, const Bounds& box, Vec3 point) {
    std::array<Vec3, 9> hull;
    for (size_t c = 0; c < 8; ++c)
        hull[c] = {(c & 1) ? box.maxs.x : box.mins.x, (c & 2) ? box.maxs.y : box.mins.y,
                   (c & 4) ? box.maxs.z : box.mins.z};
    hull[8] = point;
    return tree.hullClearOfSolid(hull);
}

void lightGridBlocks(const GridLattice& grid, std::span<const Light> lights, float margin,
                     const ContributionSettings& settings, int blockEdge, int threads, Progress& progress,
                     const GridBlockFn& lightBlock, const BspTree* solidTree) {
    const std::vector<GridBlock> blocks = gridBlocks(grid.bounds, blockEdge);
    const size_t bx = size_t(grid.bounds[0]), by = size_t(grid.bounds[1]);
    const std::vector<float> envelopes = lightEnvelopes(lights, settings.forceFast);
    const LightReach reach(lights, envelopes);
    auto body = [&](const tbb::blocked_range<size_t>& range) {
        BlockLights reaching;
        std::vector<GridBlockPoint> points;
        for (size_t b = range.begin(); b != range.end(); ++b) {
            const GridBlock& block = blocks[b];
            const Bounds bounds = gridBlockBounds(block, grid.mins, grid.size, margin);
            gridLightsReaching(lights, reach, bounds, settings, reaching.candidates);
            reaching.clearOfSolid.clear();
            if (solidTree) {
                // Sun rays run to the sky, not to an origin: they keep their own walk.
                for (const uint32_t i : reaching.candidates)
                    reaching.clearOfSolid.push_back(
                        lights[i].type != LightType::Sun && gridBoxToPointClear(*solidTree, bounds, lights[i].origin) ? 1 : 0);
            }
            points.clear();
            block.forEachPoint([&](int x, int y, int z) {
                const Vec3 origin{grid.mins.x + float(x) * grid.size.x, grid.mins.y + float(y) * grid.size.y,
                                  grid.mins.z + float(z) * grid.size.z};
                points.push_back({size_t(x) + size_t(y) * bx + size_t(z) * bx * by, origin});
            });
            lightBlock(points, reaching);
            progress.advance(block.pointCount());
        }
    };
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 1), body); });
}

void traceBlockContributions(std::span<const Light> lights, std::span<const uint32_t> candidates,
                             std::span<const uint8_t> clearOfSolid, std::span<const float> envelopes,
                             std::span<const Vec3> origins, std::span<const int> clusters, const LightingEnv& env,
                             bool coherent, bool axialRaysAlone, const std::function<bool(const Light&)>& includes,
                             const BlockContributionFn& visit) {
    // Per (light, point): its unoccluded contribution and the index of its shadow ray (-1: none).
    struct Scratch {
        std::vector<std::optional<LightContribution>> pending;
        std::vector<int32_t> rayOf;
        std::vector<ShadowRay> rays;
        std::vector<Vec3> transmission;
        std::vector<Bounds> runBoxes;
        std::vector<uint32_t> which;  // the points a light is asked about
    };
    thread_local Scratch s;
    const size_t np = origins.size(), nl = candidates.size();
    s.pending.assign(nl * np, std::nullopt);
    s.rayOf.assign(nl * np, -1);
    s.rays.clear();
    LightingEnv deferred = env;
    deferred.deferredRays = env.scene ? &s.rays : nullptr;
    LightingEnv deferredClear = deferred;
    deferredClear.clearOfSolid = true;
    // Area lights are culled for the whole block before; runs of a few points, boxed tightly, drop
    // most of the pairs the per-point bound would drop, at one test per run.
    constexpr size_t kRun = 8;
    s.runBoxes.assign((np + kRun - 1) / kRun, Bounds{});
    for (size_t p = 0; p < np; ++p) s.runBoxes[p / kRun].add(origins[p]);
    for (size_t k = 0; k < nl; ++k) {
        const Light& light = lights[candidates[k]];
        if (!includes(light)) continue;
        const LightingEnv& lightEnv = !clearOfSolid.empty() && clearOfSolid[k] ? deferredClear : deferred;
        const bool area = light.type == LightType::Area;
        s.which.clear();
        for (size_t p = 0; p < np; ++p) {
            if (area && p % kRun == 0 && areaLightSurelyDarkIn(light, s.runBoxes[p / kRun], env.settings)) {
                p += kRun - 1;
                continue;
            }
            s.which.push_back(uint32_t(p));
        }
        if (gridPointsBatchable(light, lightEnv)) {
            lightToGridPoints(light, lightEnv, envelopes[candidates[k]], origins, clusters, s.which,
                              std::span(s.pending).subspan(k * np, np), std::span(s.rayOf).subspan(k * np, np));
            continue;
        }
        for (const uint32_t p : s.which) {
            const size_t before = s.rays.size();
            std::optional<LightContribution> c =
                lightToGridPoint(light, origins[p], clusters[p], lightEnv, envelopes[candidates[k]]);
            if (!c) {
                s.rays.resize(before);
                continue;
            }
            s.pending[k * np + p] = c;
            if (s.rays.size() > before) s.rayOf[k * np + p] = int32_t(before);
        }
    }
    // Without a scene nothing is traced: all open.
    s.transmission.assign(s.rays.size(), Vec3{1, 1, 1});
    if (env.scene && !s.rays.empty()) env.scene->traceBatch(s.rays, s.transmission, coherent, axialRaysAlone);
    // Lights outer, points inner: the pending entries are read in the order they are stored, and
    // each point still receives its lights in light order.
    for (size_t k = 0; k < nl; ++k)
        for (size_t p = 0; p < np; ++p) {
            std::optional<LightContribution>& c = s.pending[k * np + p];
            if (!c) continue;
            const int32_t ray = s.rayOf[k * np + p];
            const Vec3* transmission = ray >= 0 ? &s.transmission[size_t(ray)] : nullptr;
            if (transmission) c->color *= *transmission;
            visit(p, candidates[k], *c, transmission);
        }
}

void lightGridByBlocks(const GridLattice& grid, std::span<const Light> lights, float margin,
                       const ContributionSettings& settings,
                       int blockEdge, int threads, Progress& progress, const GridPointFn& lightPoint,
                       const BspTree* solidTree) {
    lightGridBlocks(
        grid, lights, margin, settings, blockEdge, threads, progress,
        [&](std::span<const GridBlockPoint> points, const BlockLights& reaching) {
            for (const GridBlockPoint& p : points) lightPoint(p.index, p.origin, reaching);
        },
        solidTree);
}

}  // namespace q3::light
