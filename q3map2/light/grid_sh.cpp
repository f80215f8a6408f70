// TraceGridSH: the light of every grid point as L2 irradiance (see grid_sh.h and specs/sh-grid.md).
// The light list, occlusion and falloff are those of the legacy grid (lightToGridPoint); only the
// way a contribution is stored differs: projected from its true direction instead of being folded
// into one ambient + directed pair.

#include <algorithm>
#include <cmath>

#include "grid_blocks.h"
#include "grid_sh.h"
#include "grid_sh_gather.h"
#include "light_context.h"
#include "light_contribution.h"
#include "light_text.h"
#include "progress.h"

namespace q3::light {
namespace {

constexpr int kMaxAreaSubdivisions = 8;    // pieces per triangle edge for emitters close to a point
constexpr float kPiecesPerRadius = 4.0f;   // pieces per edge ~ this * emitter radius / distance
// Emitters adding less than this (legacy units, 255 = white) are one directional sample: spreading
// so little light over its true directions changes no probe by more than a fraction of a unit.
constexpr float kMinPiecedLight = 2.0f;
constexpr float kAreaPushDistance = 8.0f;  // points this close to an emitter plane are pushed off it
constexpr int kBlockEdge = 4;              // grid points per block edge (lights culled per block)

sh::Vec3d toSh(Vec3 v) { return {v.x, v.y, v.z}; }
sh::Rgb toRgb(Vec3 v, double scale) { return {v.x * scale, v.y * scale, v.z * scale}; }

struct Vec3dMath {
    double x, y, z;
};
double dot3(Vec3dMath a, Vec3dMath b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double len3(Vec3dMath a) { return std::sqrt(dot3(a, a)); }
Vec3dMath sub3(Vec3 a, Vec3 b) { return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; }

// Solid angle of the triangle (a, b, c) seen from the origin (Van Oosterom and Strackee 1983).
double triangleSolidAngle(Vec3dMath a, Vec3dMath b, Vec3dMath c) {
    const Vec3dMath bc{b.y * c.z - b.z * c.y, b.z * c.x - b.x * c.z, b.x * c.y - b.y * c.x};
    const double numerator = std::abs(dot3(a, bc));
    const double la = len3(a), lb = len3(b), lc = len3(c);
    const double denominator = la * lb * lc + dot3(a, b) * lc + dot3(a, c) * lb + dot3(b, c) * la;
    return 2.0 * std::atan2(numerator, denominator);
}

int chooseAreaSubdivisions(const Light& light, Vec3 pushed) {
    float radius = 0;
    for (const Vec3& w : light.winding) radius = std::max(radius, distance(w, light.origin));
    const float d = distance(pushed, light.origin);
    if (d <= 0) return kMaxAreaSubdivisions;
    return std::clamp(static_cast<int>(std::ceil(kPiecesPerRadius * radius / d)), 1, kMaxAreaSubdivisions);
}

// A Lambertian emitter of the q3map2 model sends light.add / pi (legacy units) per steradian: the
// legacy form factor is the projected solid angle / pi times light.add. Each piece adds its solid
// angle times that radiance as a directional sample. The emitter is shadowed as a whole by the
// legacy grid's ray (`transmission`): the pieces spread its light over the directions it covers,
// at no extra rays, and the SH grid sees exactly the occlusion the legacy grid sees.
void addAreaPieces(sh::SH9Color& acc, const Light& light, Vec3 pushed, int pieces, Vec3 transmission) {
    const double radiance = double(light.add) / sh::kPi;
    const size_t n = light.winding.size();
    const float step = 1.0f / float(pieces);
    auto at = [&](Vec3 p0, Vec3 e1, Vec3 e2, int i, int j) {
        return p0 + e1 * (float(i) * step) + e2 * (float(j) * step);
    };
    auto addPiece = [&](Vec3 a, Vec3 b, Vec3 c) {
        const double omega = triangleSolidAngle(sub3(a, pushed), sub3(b, pushed), sub3(c, pushed));
        if (!(omega > 0)) return;
        const Vec3 centroid = (a + b + c) / 3.0f;
        const Vec3 dir = normalize(centroid - pushed);
        if (dir == Vec3{}) return;
        const double scale = radiance * omega / 255.0;
        sh::addDirectionalIrradiance(acc, toSh(dir), toRgb(light.color * transmission, scale));
    };
    for (size_t t = 1; t + 1 < n; ++t) {
        const Vec3 p0 = light.winding[0];
        const Vec3 e1 = light.winding[t] - p0;
        const Vec3 e2 = light.winding[t + 1] - p0;
        for (int i = 0; i < pieces; ++i)
            for (int j = 0; i + j < pieces; ++j) {
                addPiece(at(p0, e1, e2, i, j), at(p0, e1, e2, i + 1, j), at(p0, e1, e2, i, j + 1));
                if (i + j + 1 < pieces)
                    addPiece(at(p0, e1, e2, i + 1, j), at(p0, e1, e2, i + 1, j + 1), at(p0, e1, e2, i, j + 1));
            }
    }
}

bool isBlack(const sh::GridPointSH& p) {
    for (const auto& c : p.coeffs)
        if (c[0] != 0 || c[1] != 0 || c[2] != 0) return false;
    return true;
}

}  // namespace

std::optional<LightContribution> addLightToGridPointSH(sh::SH9Color& acc, const Light& light, Vec3 origin,
                                                       int cluster, const LightingEnv& env, int areaSubdivisions) {
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
    const sh::Rgb color = toRgb(c->color, 1.0 / 255.0);
    if (light.controlled && light.type != LightType::Sun) {
        sh::addControlledIncidence(acc, toSh(c->direction), color, light.controlled->dotProductWeight);
        return c;
    }
    if (light.type == LightType::Area && !env.settings.faster && light.winding.size() >= 3) {
        const float d = dot(origin, light.normal) - light.planeDist;
        const bool nearPlane = d > -kAreaPushDistance && d < kAreaPushDistance;
        const Vec3 pushed = nearPlane ? origin + light.normal * (kAreaPushDistance - d) : origin;
        const bool faint = maxComponent(c->color) < kMinPiecedLight;
        const int pieces = areaSubdivisions > 0 ? areaSubdivisions : faint ? 1 : chooseAreaSubdivisions(light, pushed);
        if (pieces > 1) {
            addAreaPieces(acc, light, pushed, pieces, transmission);
            return c;
        }
    }
    // Points, spots, suns (each jittered sun sample and each sky-dome sun is its own light), far
    // area lights: one directional sample, as the legacy grid sees it.
    sh::addDirectionalIrradiance(acc, toSh(c->direction), color);
    return c;
}

void applyAmbientAndFloor(sh::SH9Color& acc, Vec3 ambient, Vec3 minLight) {
    sh::addAmbient(acc, toRgb(ambient, 1.0 / 255.0));
    const double y0 = sh::evalBasis({0, 0, 1})[0];
    for (int ch = 0; ch < 3; ++ch) {
        const double floor = minLight[ch] / 255.0;
        if (acc.c[0][ch] * y0 < floor) acc.c[0][ch] = floor / y0;
    }
}

uint64_t fillFromNeighbours(std::vector<sh::GridPointSH>& points, std::vector<uint8_t>& unset,
                            std::array<int, 3> bounds) {
    const int bx = bounds[0], by = bounds[1], bz = bounds[2];
    const size_t count = points.size();
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
    std::vector<sh::GridPointSH> values;
    while (!frontier.empty()) {
        // Every value of a pass reads only points set before it, so the order inside a pass does not matter.
        values.assign(frontier.size(), sh::GridPointSH{});
        for (size_t f = 0; f < frontier.size(); ++f) {
            double sum[9][3] = {};
            int n = 0;
            forNeighbours(frontier[f], [&](size_t j) {
                if (unset[j]) return;
                ++n;
                for (int k = 0; k < 9; ++k)
                    for (int ch = 0; ch < 3; ++ch) sum[k][ch] += points[j].coeffs[k][ch];
            });
            for (int k = 0; k < 9; ++k)
                for (int ch = 0; ch < 3; ++ch) values[f].coeffs[k][ch] = float(sum[k][ch] / std::max(1, n));
        }
        std::vector<size_t> next;
        for (size_t f = 0; f < frontier.size(); ++f) {
            points[frontier[f]] = values[f];
            unset[frontier[f]] = 0;
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

sh::GridSH traceGridSH(const LightContext& ctx, const ShGridLayout& layout, Log& log, ShTraceStats* statsOut) {
    sh::GridSH grid;
    for (int axis = 0; axis < 3; ++axis) {
        grid.mins[axis] = layout.mins[axis];
        grid.size[axis] = layout.size[axis];
        grid.bounds[axis] = layout.bounds[axis];
    }
    const size_t numPoints = static_cast<size_t>(layout.numPoints());
    grid.points.assign(numPoints, sh::GridPointSH{});

    const LightingEnv env = gridLightingEnv(ctx);
    const bool useTree = ctx.tree && ctx.tree->hasNodes();
    const float nudgeRadius = 0.5f * maxComponent(layout.size);
    // Offsets half the radius apart (33 positions): a point deep in solid costs one tree walk per
    // position, and solid points are filled from their neighbours afterwards anyway.
    const std::vector<Vec3> offsets = useTree ? nudgeOffsets(nudgeRadius, std::max(1.0f, nudgeRadius / 2.0f))
                                              : std::vector<Vec3>{};
    const float gridScale = ctx.options.gridScale;

    std::vector<uint8_t> solid(numPoints, 0), nudged(numPoints, 0);
    std::vector<Vec3> origins(numPoints);
    log.info(strCat("SH light grid: ", numPoints, " points"));
    Progress progress = Progress::forConsole(log, numPoints);
    auto lightPoint = [&](size_t i, Vec3 lattice, std::span<const uint32_t> candidates) {
        const std::optional<PlacedGridPoint> placed = placeGridPoint(ctx.tree.get(), lattice, offsets);
        if (!placed) {
            solid[i] = 1;
            return;
        }
        nudged[i] = placed->nudged ? 1 : 0;
        const Vec3 origin = placed->origin;
        const int cluster = placed->cluster;
        origins[i] = origin;
        sh::SH9Color acc;
        Vec3 total = ctx.world.ambient;
        for (uint32_t lightIndex : candidates) {
            const Light& light = ctx.lights[lightIndex];
            if (light.style != 0) continue;  // IBSP grids hold style 0 only (styled light is switchable)
            std::optional<LightContribution> c = addLightToGridPointSH(acc, light, origin, cluster, env);
            if (!c) continue;
            total += c->color;
            if (ctx.options.cheapGrid && total.x >= 255 && total.y >= 255 && total.z >= 255) break;
        }
        applyAmbientAndFloor(acc, ctx.world.ambient, ctx.world.minGridLight);
        grid.points[i] = sh::toGridPoint(sh::scale(acc, gridScale));
    };
    // Nudged points move at most nudgeRadius from their lattice position.
    lightGridByBlocks(GridLattice{layout.bounds, layout.mins, layout.size}, ctx.lights, nudgeRadius + 1.0f,
                      env.settings.forceFast, kBlockEdge, ctx.threads, progress, lightPoint);
    progress.finish();

    ShTraceStats stats;
    stats.points = numPoints;
    stats.bounds = layout.bounds;
    for (size_t i = 0; i < numPoints; ++i) {
        stats.nudged += nudged[i];
        stats.inSolid += solid[i];
        stats.blackBeforeFill += isBlack(grid.points[i]) ? 1 : 0;
    }
    stats.solid = solid;
    stats.origins = std::move(origins);
    std::vector<uint8_t> unset = solid;
    stats.filled = fillFromNeighbours(grid.points, unset, layout.bounds);
    for (const sh::GridPointSH& p : grid.points) stats.blackAfterFill += isBlack(p) ? 1 : 0;
    log.info(strCat("SH grid: ", stats.nudged, " points nudged out of solid, ", stats.inSolid, " in solid, ",
                    stats.filled, " filled from neighbours, ", stats.blackBeforeFill, " black before the fill, ",
                    stats.blackAfterFill, " after"));
    if (statsOut) *statsOut = std::move(stats);
    return grid;
}

ShTraceStats lightGridSH(LightContext& ctx, Log& log) {
    ShTraceStats stats;
    if (!ctx.options.sh && !ctx.options.shBspx) return stats;
    const ShGridLayout layout = setupGridSH(ctx, log);
    bsp::detachShGrid(ctx.bsp);  // an SH grid of the input BSP is not kept beside the new one
    sh::GridSH grid = traceGridSH(ctx, layout, log, &stats);
    if (ctx.options.shGather) {  // indirect light on top of the direct light traced above
        const ShGatherStats gathered = gatherIndirectSH(ctx, shaderAlbedo(ctx, log), grid, stats, log);
        ctx.stats.shGatherRays = gathered.rays;
        ctx.stats.shGatherSeconds = gathered.seconds;
    }
    attachGridSH(ctx.bsp, grid, ctx.options.shBspx);
    return stats;
}

}  // namespace q3::light
