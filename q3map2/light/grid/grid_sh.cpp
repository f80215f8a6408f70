// TraceGridSH: the light of every grid point as L2 irradiance (see grid_sh.h and specs/sh-grid.md).
// The light list, occlusion and falloff are those of the legacy grid (lightToGridPoint); only the
// way a contribution is stored differs: projected from its true direction instead of being folded
// into one ambient + directed pair.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "grid_blocks.h"
#include "grid_sh.h"

#include "grid_encode.h"
#include "grid_sh_corners.h"
#include "grid_sh_gather.h"
#include "light_context.h"
#include "light_contribution.h"
#include "light_text.h"
#include "progress.h"
#include "sh_polygon.h"
#include "world_lights_export.h"

namespace q3::light {
namespace {

// Emitters adding less than this (legacy units, 255 = white) are one directional sample: spreading
// so little light over its true directions changes no probe by more than a fraction of a unit.
constexpr float kMinSpreadLight = 2.0f;
// Emitters farther than this many times their radius are one directional sample: the L2 projection
// of the whole emitter then differs from it by under 2 % of its peak.
constexpr float kOneSampleDistance = 4.0f;
constexpr float kAreaPushDistance = 8.0f;  // points this close to an emitter plane are pushed off it
constexpr int kBlockEdge = 4;              // grid points per block edge (lights culled per block)

sh::Vec3d toSh(Vec3 v) { return {v.x, v.y, v.z}; }
sh::Rgb toRgb(Vec3 v, double scale) { return {v.x * scale, v.y * scale, v.z * scale}; }

bool closeToEmitter(const Light& light, Vec3 pushed) {
    float radius = 0;
    for (const Vec3& w : light.winding) radius = std::max(radius, distance(w, light.origin));
    return distance(pushed, light.origin) < kOneSampleDistance * radius;
}

// A Lambertian emitter of the q3map2 model sends light.add / pi (legacy units) per steradian: the
// legacy form factor is the projected solid angle / pi times light.add. The SH grid integrates that
// radiance over the directions the emitter covers (sh_polygon.h). The emitter is shadowed as a
// whole by the legacy grid's ray (`transmission`), so the SH grid sees exactly the occlusion the
// legacy grid sees.
void addAreaEmitter(sh::SH9Color& acc, const Light& light, Vec3 pushed, Vec3 transmission) {
    thread_local std::vector<sh::Vec3d> corners;
    corners.clear();
    for (const Vec3& w : light.winding) corners.push_back(toSh(w - pushed));
    const double radiance = double(light.add) / sh::kPi / 255.0;
    sh::addUniformPolygonIrradiance(acc, sh::sphericalPolygonMoments(corners),
                                    toRgb(light.color * transmission, radiance));
}

}  // namespace

constexpr float kFarFromBlock = 1.0f;
bool farFromBlock(const Light& light, const Bounds& box) {
    if (light.type == LightType::Sun) return true;
    Vec3 centre = light.origin;
    float radius = 0;
    if (light.type == LightType::Area && light.emitter.radius >= 0) {
        centre = light.emitter.center;
        radius = light.emitter.radius;
    }
    const Vec3 nearest = vmin(vmax(centre, box.mins), box.maxs);
    return distance(nearest, centre) - radius >= kFarFromBlock * maxComponent(box.maxs - box.mins);
}

namespace {

bool isBlack(const sh::GridPointSH& p) {  // every coefficient zero
    for (const auto& c : p.coeffs)
        if (c[0] != 0 || c[1] != 0 || c[2] != 0) return false;
    return true;
}

}  // namespace

bool projectContribution(sh::SH9Color& acc, const Light& light, Vec3 origin, const LightContribution& c,
                         Vec3 transmission, const ContributionSettings& settings, bool areaAsOneSample) {
    const sh::Rgb color = toRgb(c.color, 1.0 / 255.0);
    if (light.controlled && light.type != LightType::Sun) {
        sh::addControlledIncidence(acc, toSh(c.direction), color, light.controlled->dotProductWeight);
        return false;
    }
    if (light.type == LightType::Area && !settings.faster && !areaAsOneSample && light.winding.size() >= 3) {
        const float d = dot(origin, light.normal) - light.planeDist;
        const bool nearPlane = d > -kAreaPushDistance && d < kAreaPushDistance;
        const Vec3 pushed = nearPlane ? origin + light.normal * (kAreaPushDistance - d) : origin;
        if (maxComponent(c.color) >= kMinSpreadLight && closeToEmitter(light, pushed)) {
            addAreaEmitter(acc, light, pushed, transmission);
            return true;
        }
    }
    // Points, spots, suns (each jittered sun sample and each sky-dome sun is its own light), far
    // area lights: one directional sample, as the legacy grid sees it.
    sh::addDirectionalIrradiance(acc, toSh(c.direction), color);
    return false;
}

std::optional<LightContribution> addLightToGridPointSH(sh::SH9Color& acc, const Light& light, Vec3 origin,
                                                       int cluster, const LightingEnv& env, bool areaAsOneSample) {
    // The legacy contribution, unoccluded, with its shadow ray set aside; traced once below.
    thread_local std::vector<ShadowRay> ray;  // at most one ray; kept to avoid an allocation per call
    ray.clear();
    LightingEnv deferred = env;
    deferred.deferredRays = env.scene ? &ray : nullptr;
    std::optional<LightContribution> c = lightToGridPoint(light, origin, cluster, deferred);
    if (!c) return c;
    Vec3 transmission{1, 1, 1};
    if (!ray.empty()) env.scene->traceBatch(ray, std::span<Vec3>(&transmission, 1));
    if (transmission == Vec3{}) return std::nullopt;
    c->color *= transmission;
    projectContribution(acc, light, origin, *c, transmission, env.settings, areaAsOneSample);
    return c;
}

void addLightsToGridPointSH(sh::SH9Color& acc, std::span<const Light> lights, std::span<const uint32_t> candidates,
                            Vec3 origin, int cluster, const LightingEnv& env) {
    addLightsToGridPointsSH(std::span<sh::SH9Color>(&acc, 1), lights, candidates, {}, {}, std::span<const Vec3>(&origin, 1),
                            std::span<const int>(&cluster, 1), env);
}

void addLightsToGridPointsSH(std::span<sh::SH9Color> accs, std::span<const Light> lights,
                             std::span<const uint32_t> candidates, std::span<const uint8_t> clearOfSolid,
                             std::span<const float> envelopes, std::span<const Vec3> origins,
                             std::span<const int> clusters, const LightingEnv& env) {
    thread_local std::vector<float> ownEnvelopes;
    if (envelopes.empty()) {  // one probe's call: only the candidates' envelopes are read
        ownEnvelopes.assign(lights.size(), 0.0f);
        for (uint32_t i : candidates) ownEnvelopes[i] = lightEnvelope(lights[i], env.settings.forceFast);
        envelopes = ownEnvelopes;
    }
    const BlockContributionFn visit = [&](size_t p, uint32_t lightIndex, const LightContribution& c,
                                          const Vec3* transmission) {
        const Vec3 t = transmission ? *transmission : Vec3{1, 1, 1};
        if (t == Vec3{}) return;
        projectContribution(accs[p], lights[lightIndex], origins[p], c, t, env.settings, false);
    };
    const std::function<bool(const Light&)> styleZero = [](const Light& light) {
        return light.style == 0;  // IBSP grids hold style 0 only (styled light is switchable)
    };
    // One stream per block, flagged incoherent: the rays spread from the probes towards every light
    // (measured faster than one call per ray and than a coherent stream on oacmpctf1 and oacmpdm4).
    traceBlockContributions(lights, candidates, clearOfSolid, envelopes, origins, clusters, env, false, false,
                            styleZero, visit);
}

void applyAmbientAndFloor(sh::SH9Color& acc, Vec3 ambient, Vec3 minLight) {
    sh::addAmbient(acc, toRgb(ambient, 1.0 / 255.0));
    const double y0 = sh::evalBasis({0, 0, 1})[0];
    for (int ch = 0; ch < 3; ++ch) {
        const double floor = minLight[ch] / 255.0;
        if (acc.c[0][ch] * y0 < floor) acc.c[0][ch] = floor / y0;
    }
}

uint64_t fillFromNeighbours(sh::GridLumpImage& grid, std::vector<uint8_t>& unset) {
    const std::array<int32_t, 3> bounds = grid.bounds();
    const int bx = bounds[0], by = bounds[1], bz = bounds[2];
    const size_t count = grid.numPoints();
    auto indexOf = [&](int x, int y, int z) { return size_t(x) + size_t(y) * bx + size_t(z) * bx * by; };
    auto forNeighbours = [&](size_t i, auto&& visit) {
        const int x = int(i % size_t(bx)), y = int((i / size_t(bx)) % size_t(by)), z = int(i / (size_t(bx) * by));
        if (x > 0) visit(indexOf(x - 1, y, z));
        if (x + 1 < bx) visit(indexOf(x + 1, y, z));
        if (y > 0) visit(indexOf(x, y - 1, z));
        if (y + 1 < by) visit(indexOf(x, y + 1, z));
        if (z > 0) visit(indexOf(x, y, z - 1));
        if (z + 1 < bz) visit(indexOf(x, y, z + 1));
    };
    // First frontier: unset points touching a set one, in index order.
    std::vector<size_t> frontier;
    std::vector<uint8_t> queued(count, 0);
    for (size_t i = 0; i < count; ++i) {
        if (!unset[i]) continue;
        bool touches = false;
        forNeighbours(i, [&](size_t j) { touches = touches || !unset[j]; });
        if (touches) {
            frontier.push_back(i);
            queued[i] = 1;
        }
    }
    uint64_t filled = 0;
    while (!frontier.empty()) {
        // Every value of a pass reads only points set before it (frontier points stay unset until
        // the pass ends), so each is written in place and the order inside a pass does not matter.
        for (size_t i : frontier) {
            double sum[9][3] = {};
            int n = 0;
            forNeighbours(i, [&](size_t j) {
                if (unset[j]) return;
                ++n;
                const sh::GridPointSH neighbour = grid.point(j);
                for (int k = 0; k < 9; ++k)
                    for (int ch = 0; ch < 3; ++ch) sum[k][ch] += neighbour.coeffs[k][ch];
            });
            sh::GridPointSH value;
            for (int k = 0; k < 9; ++k)
                for (int ch = 0; ch < 3; ++ch) value.coeffs[k][ch] = float(sum[k][ch] / std::max(1, n));
            grid.setPoint(i, value);
        }
        std::vector<size_t> next;
        for (size_t i : frontier) {
            unset[i] = 0;
            ++filled;
        }
        for (size_t i : frontier)
            forNeighbours(i, [&](size_t j) {
                if (unset[j] && !queued[j]) {
                    queued[j] = 1;
                    next.push_back(j);
                }
            });
        std::sort(next.begin(), next.end());
        frontier = std::move(next);
    }
    return filled;
}

sh::GridLumpImage traceGridSH(const LightContext& ctx, const ShGridLayout& layout, Log& log, ShTraceStats* statsOut) {
    const float mins[3] = {layout.mins.x, layout.mins.y, layout.mins.z};
    const float size[3] = {layout.size.x, layout.size.y, layout.size.z};
    const int32_t bounds[3] = {layout.bounds[0], layout.bounds[1], layout.bounds[2]};
    sh::GridLumpImage grid(mins, size, bounds);
    const size_t numPoints = grid.numPoints();

    // The same contributions as the legacy grid, inhibit radius included (its cells, not ours).
    const std::string gridSizeValue = ctx.entities.empty() ? std::string() : ctx.entities[0].value("gridsize");
    const Vec3 legacyCell =
        computeGridLayout(parseGridSize(gridSizeValue, ctx.bspPath.string() + ": worldspawn \"gridsize\""), ctx.bsp).size;
    const LightingEnv env = gridLightingEnv(ctx, legacyCell);
    const bool useTree = ctx.tree && ctx.tree->hasNodes();
    const float nudgeRadius = 0.5f * maxComponent(layout.size);
    // Offsets half the radius apart (33 positions): a point deep in solid costs one tree walk per
    // position, and solid points are filled from their neighbours afterwards anyway.
    const GridNudges offsets(useTree ? nudgeOffsets(nudgeRadius, std::max(1.0f, nudgeRadius / 2.0f))
                                     : std::vector<Vec3>{});
    const float gridScale = ctx.options.gridScale;
    // -shnoworldlights: the lights the WORLDLIGHTS lump lists give the SH grid no direct light.
    const WorldLightSettings listing = worldLightSettings(ctx.options);
    std::vector<uint8_t> outOfGrid(ctx.lights.size(), 0);
    size_t leftOut = 0;
    for (size_t i = 0; i < ctx.lights.size(); ++i) leftOut += outOfGrid[i] = keptOutOfShGrid(ctx.lights[i], listing);
    if (leftOut) log.info(strCat("SH grid: the direct light of ", leftOut, " world lights is left out (-shnoworldlights)"));

    std::vector<uint8_t> solid(numPoints, 0), nudged(numPoints, 0);
    std::vector<Vec3> origins(ctx.options.shGather ? numPoints : 0);  // only the gather reads them
    log.info(strCat("SH light grid: ", numPoints, " points"));
    Progress progress = Progress::forConsole(log, numPoints);
    // Where a point is lit: its lattice position or the nearest free nudge; false when in solid.
    auto place = [&](size_t i, Vec3 lattice) -> std::optional<PlacedGridPoint> {
        std::optional<PlacedGridPoint> placed = placeGridPoint(ctx.tree.get(), lattice, offsets);
        if (!placed) {
            solid[i] = 1;
            return placed;
        }
        nudged[i] = placed->nudged ? 1 : 0;
        if (!origins.empty()) origins[i] = placed->origin;
        return placed;
    };
    auto store = [&](size_t i, sh::SH9Color& acc) {
        applyAmbientAndFloor(acc, ctx.world.ambient, ctx.world.minGridLight);
        grid.setPoint(i, sh::toGridPoint(sh::scale(acc, gridScale)));
    };
    const GridLattice lattice{layout.bounds, layout.mins, layout.size};
    std::atomic<uint64_t> sharedPairs{0};
    if (ctx.options.cheapGrid) {
        // -cheapgrid stops once the point is white, so each light's ray is traced before the next.
        auto lightPoint = [&](size_t i, Vec3 latticePoint, const BlockLights& reaching) {
            const std::optional<PlacedGridPoint> placed = place(i, latticePoint);
            if (!placed) return;
            sh::SH9Color acc;
            Vec3 total = ctx.world.ambient;
            for (uint32_t lightIndex : reaching.candidates) {
                const Light& light = ctx.lights[lightIndex];
                if (light.style != 0 || outOfGrid[lightIndex]) continue;  // IBSP grids hold style 0 only (styled light is switchable)
                std::optional<LightContribution> c = addLightToGridPointSH(acc, light, placed->origin, placed->cluster, env);
                if (!c) continue;
                total += c->color;
                if (total.x >= 255 && total.y >= 255 && total.z >= 255) break;
            }
            store(i, acc);
        };
        // Nudged points move at most nudgeRadius from their lattice position.
        lightGridByBlocks(lattice, ctx.lights, nudgeRadius + 1.0f, env.settings, kBlockEdge, ctx.threads, progress,
                          lightPoint);
    } else if (!ctx.options.shExact) {
        const std::vector<float> envelopes = lightEnvelopes(ctx.lights, env.settings.forceFast);
        const ShPointSink sink{[&](size_t i, Vec3 latticePoint) { return place(i, latticePoint); },
                               [&](size_t i, sh::SH9Color& acc) { store(i, acc); }};
        sharedPairs = traceGridSHSharedCorners(lattice, ctx.lights, outOfGrid, envelopes, env, nudgeRadius + 1.0f,
                                               useTree ? ctx.tree.get() : nullptr, ctx.threads, progress, sink);
    } else {
        // -shexact: every light lit and traced at every point, block by block (the shadow rays of
        // all the block's probes go to the scene as one stream, and lights whose rays from the
        // whole block meet no structural solid skip the tree walk).
        const std::vector<float> envelopes = lightEnvelopes(ctx.lights, env.settings.forceFast);
        auto lightBlock = [&](std::span<const GridBlockPoint> blockPoints, const BlockLights& reaching) {
            thread_local std::vector<size_t> index;
            thread_local std::vector<Vec3> at;
            thread_local std::vector<int> clusters;
            thread_local std::vector<sh::SH9Color> accs;
            thread_local std::vector<uint32_t> candidates;
            thread_local std::vector<uint8_t> clearOfSolid;
            index.clear();
            at.clear();
            clusters.clear();
            for (const GridBlockPoint& p : blockPoints)
                if (const std::optional<PlacedGridPoint> placed = place(p.index, p.origin)) {
                    index.push_back(p.index);
                    at.push_back(placed->origin);
                    clusters.push_back(placed->cluster);
                }
            accs.assign(index.size(), sh::SH9Color{});
            // The candidates were culled for the block grown by the farthest nudge; most blocks
            // nudge no point, and their own points' box drops more lights.
            Bounds placedBox;
            for (const Vec3& o : at) placedBox.add(o);
            candidates.clear();
            clearOfSolid.clear();
            for (size_t k = 0; k < reaching.candidates.size(); ++k) {
                const uint32_t i = reaching.candidates[k];
                if (outOfGrid[i] || !lightReachesBounds(ctx.lights[i], placedBox, envelopes[i]) ||
                    !mayLightGridIn(ctx.lights[i], placedBox, env.settings))
                    continue;
                candidates.push_back(i);
                if (!reaching.clearOfSolid.empty()) clearOfSolid.push_back(reaching.clearOfSolid[k]);
            }
            addLightsToGridPointsSH(accs, ctx.lights, candidates, clearOfSolid, envelopes, at, clusters, env);
            for (size_t k = 0; k < index.size(); ++k) store(index[k], accs[k]);
        };
        lightGridBlocks(lattice, ctx.lights, nudgeRadius + 1.0f, env.settings, kBlockEdge, ctx.threads, progress,
                        lightBlock, useTree ? ctx.tree.get() : nullptr);
    }
    progress.finish();

    ShTraceStats stats;
    stats.points = numPoints;
    stats.bounds = layout.bounds;
    stats.sharedPairs = sharedPairs.load();
    for (size_t i = 0; i < numPoints; ++i) {
        stats.nudged += nudged[i];
        stats.inSolid += solid[i];
        stats.blackBeforeFill += isBlack(grid.point(i)) ? 1 : 0;
    }
    std::vector<uint8_t>().swap(nudged);  // counted: freed before the fill
    std::vector<uint8_t> unset = solid;
    stats.solid = std::move(solid);
    stats.origins = std::move(origins);
    stats.filled = fillFromNeighbours(grid, unset);
    for (size_t i = 0; i < numPoints; ++i) stats.blackAfterFill += isBlack(grid.point(i)) ? 1 : 0;
    log.info(strCat("SH grid: ", stats.nudged, " points nudged out of solid, ", stats.inSolid, " in solid, ",
                    stats.filled, " filled from neighbours, ", stats.blackBeforeFill, " black before the fill, ",
                    stats.blackAfterFill, " after, ", stats.sharedPairs, " light-probe pairs taken from their block's corners"));
    if (statsOut) *statsOut = std::move(stats);
    return grid;
}

ShTraceStats lightGridSH(LightContext& ctx, Log& log) {
    ShTraceStats stats;
    if (!ctx.options.sh && !ctx.options.shBspx) return stats;
    const ShGridLayout layout = setupGridSH(ctx, log);
    // An SH grid of the input BSP is not kept beside the new one: lump 18 is dropped, a BSPX copy
    // emptied in its slot (attachGridSH fills or removes it, so the trailer's order is kept).
    bsp::detachShGrid(ctx.bsp);
    if (ctx.bsp.findBspx(sh::kBspxLumpName)) ctx.bsp.setBspx(sh::kBspxLumpName, {});
    sh::GridLumpImage grid = traceGridSH(ctx, layout, log, &stats);
    if (ctx.options.shGather) {  // indirect light on top of the direct light traced above
        const ShGatherStats gathered = gatherIndirectSH(ctx, shaderAlbedo(ctx, log), grid, stats, log);
        ctx.stats.shGatherRays = gathered.rays;
        ctx.stats.shGatherSeconds = gathered.seconds;
    }
    attachGridSH(ctx.bsp, std::move(grid), ctx.options.shBspx);
    return stats;
}

}  // namespace q3::light
