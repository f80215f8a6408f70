// Grid points are lit block by block (a few points along each axis), so that the lights whose
// envelope cannot reach a block are dropped once for the whole block instead of once per point.
// Shared by the legacy grid and the SH grid; results do not depend on the block size because the
// surviving lights keep their order.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "bsp_tree.h"
#include "c_library_random.h"
#include "light_contribution.h"
#include "light_reach.h"
#include "lights.h"
#include "vec3.h"

namespace q3 {
class Progress;
}

namespace q3::light {

struct GridBlock {
    std::array<int, 3> first{};  // first point index per axis
    std::array<int, 3> end{};    // one past the last
    template <typename Visit>
    void forEachPoint(Visit&& visit) const {
        for (int z = first[2]; z < end[2]; ++z)
            for (int y = first[1]; y < end[1]; ++y)
                for (int x = first[0]; x < end[0]; ++x) visit(x, y, z);
    }
    uint64_t pointCount() const {
        return uint64_t(end[0] - first[0]) * uint64_t(end[1] - first[1]) * uint64_t(end[2] - first[2]);
    }
};

// Blocks of up to `edge` points per axis covering a grid of `bounds` points, z-major order.
std::vector<GridBlock> gridBlocks(std::array<int, 3> bounds, int edge);

// World bounds of a block's points (`mins` + index * `size`), grown by `margin` on every side.
Bounds gridBlockBounds(const GridBlock& block, Vec3 mins, Vec3 size, float margin);

// Indices, in light order, of the lights that may light a grid point inside `bounds`: they affect
// the grid, their envelope (`envelopes`, lightEnvelope of each light) reaches the box, and area
// lights may add more than their -fast tolerance there (areaLightSurelyDarkIn).
void gridLightsReaching(std::span<const Light> lights, std::span<const float> envelopes, const Bounds& bounds,
                        const ContributionSettings& settings, std::vector<uint32_t>& out);
// Whether a light whose envelope reaches `bounds` may light a grid point inside them: it affects
// the grid and is not surely dark there (areaLightSurelyDarkIn).
bool mayLightGridIn(const Light& light, const Bounds& bounds, const ContributionSettings& settings);
// The same from an index of the lights' envelopes built once for many blocks.
void gridLightsReaching(std::span<const Light> lights, const LightReach& reach, const Bounds& bounds,
                        const ContributionSettings& settings, std::vector<uint32_t>& out);

// Whether no segment from a point of `box` to `point` enters structural solid (a hull walk of
// `tree`; false when unsure).
bool gridBoxToPointClear(const BspTree& tree, const Bounds& box, Vec3 point);

// The nudges tried for grid points in solid (nearest first), with their box taken once.
struct GridNudges {
    std::vector<Vec3> offsets;
    BspTree::OffsetBox box;
    explicit GridNudges(std::vector<Vec3> nudges) : offsets(std::move(nudges)), box(BspTree::offsetBox(offsets)) {}
};

// Where a grid point is lit: its lattice position, or the first free nudge of it when it starts in
// solid. `tree` null (or a BSP without nodes): every point is free, cluster -1. nullopt: every
// nudge stays in solid.
struct PlacedGridPoint {
    Vec3 origin;
    int cluster = -1;
    bool nudged = false;
};
std::optional<PlacedGridPoint> placeGridPoint(const BspTree* tree, Vec3 origin, const GridNudges& nudges);

// q3map2's TraceGrid nudges a point in solid by up to 199 random tries (the step grows by 0.005 from
// 0.005; each try moves the point by (Random() - 0.5) x step x `cellSize` along x, then y, then z)
// and keeps the first free one. These draw exactly as many values as q3map2 does, so calling them
// for every point in index order keeps the sequence in step with q3map2's run on one thread.
constexpr int kGridNudgeTries = 199;  // while the step, summed in double, stays within 1
// The first of the nudge tries of `origin` that may be free: every earlier try, whatever is drawn,
// lies in solid as the tries are tested (BspTree::boxInSolid decides; unsure counts as may be
// free). kGridNudgeTries when every try stays in solid.
int firstGridNudgeThatMayLeaveSolid(const BspTree& tree, Vec3 origin, Vec3 cellSize);
// The first free try for a point in solid, drawing from `random` the values its tries take. Tries
// before `firstTry` (firstGridNudgeThatMayLeaveSolid) are drawn but not tested.
std::optional<PlacedGridPoint> nudgeGridPointAsTraceGrid(const BspTree& tree, Vec3 origin, Vec3 cellSize,
                                                         CLibraryRandom& random, int firstTry = 0);

// A grid to light: `bounds` points per axis at `mins` + index * `size`.
struct GridLattice {
    std::array<int, 3> bounds{};
    Vec3 mins;
    Vec3 size;
};

// Every point of `grid` (index x + y bx + z bx by) placed as q3map2's TraceGrid places them on one
// thread, in index order, drawing from `random` (placeGridPoint, then nudgeGridPointAsTraceGrid);
// the tests that draw nothing run on `threads` threads. nullopt: left in solid. `tree` null or
// without nodes: every point stays on the lattice.
std::vector<std::optional<PlacedGridPoint>> placeGridAsTraceGrid(const BspTree* tree, const GridLattice& grid,
                                                                 CLibraryRandom random, int threads);

// The lights that may reach a block's points (indices in light order), and with a tree, for each
// of them whether no segment from anywhere in the block (nudges included) to the light's origin
// enters structural solid.
struct BlockLights {
    std::vector<uint32_t> candidates;
    std::vector<uint8_t> clearOfSolid;  // per candidate; empty without a tree
};

// Calls lightPoint(index, origin, lights) for every point (index = x + y*bx + z*bx*by), in
// parallel over blocks of `blockEdge` points per axis (`threads` 0 = one per core). The candidates
// are the lights whose envelope reaches the block grown by `margin` (how far a point may be
// nudged); `solidTree` also fills their clearOfSolid. Each point is visited once, so results
// written per index do not depend on the threads.
using GridPointFn = std::function<void(size_t index, Vec3 origin, const BlockLights& lights)>;
void lightGridByBlocks(const GridLattice& grid, std::span<const Light> lights, float margin,
                       const ContributionSettings& settings,
                       int blockEdge, int threads, Progress& progress, const GridPointFn& lightPoint,
                       const BspTree* solidTree = nullptr);

// The same walk, one call per block with all its points (for callers that trace a block's rays
// together).
struct GridBlockPoint {
    size_t index;
    Vec3 origin;
};
using GridBlockFn = std::function<void(std::span<const GridBlockPoint> points, const BlockLights& lights)>;
void lightGridBlocks(const GridLattice& grid, std::span<const Light> lights, float margin,
                     const ContributionSettings& settings, int blockEdge, int threads, Progress& progress,
                     const GridBlockFn& lightBlock, const BspTree* solidTree = nullptr);

// The lights `candidates` (indices into `lights`, in order; `clearOfSolid[k]`, when given, as in
// BlockLights) at free points `origins` / `clusters`, with their shadow rays from all the points
// traced as one batch (`coherent` and `axialRaysAlone` as TraceScene::traceBatch takes them; each
// ray gets the same answer it gets alone). Then, light by light (so each point in light order),
// visit(point, lightIndex, contribution, transmission) for every light that reaches it:
// contribution.color already multiplied by the ray's transmission (nullptr: no ray was traced).
// `includes(light)` false leaves a light out; `envelopes` holds lightEnvelope of every light.
using BlockContributionFn =
    std::function<void(size_t point, uint32_t lightIndex, const LightContribution& contribution,
                       const Vec3* transmission)>;

void traceBlockContributions(std::span<const Light> lights, std::span<const uint32_t> candidates,
                             std::span<const uint8_t> clearOfSolid, std::span<const float> envelopes,
                             std::span<const Vec3> origins, std::span<const int> clusters, const LightingEnv& env,
                             bool coherent, bool axialRaysAlone, const std::function<bool(const Light&)>& includes,
                             const BlockContributionFn& visit);

}  // namespace q3::light
