// Corner-shared SH blocks (see grid_sh_corners.h).
#include "grid_sh_corners.h"

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "grid_sh.h"
#include "light_reach.h"
#include "progress.h"
#include "trace_scene.h"

namespace q3::light {
namespace {

// Shared corners about this far apart on every axis (4 x 4 x 2 intervals of the default 32 x 32 x
// 64 cells): wider blocks interpolate more lights, narrower ones trace fewer rays from corners that
// disagree; measured on oacmpdm8 and oacmpdm10 against -shexact (tests/lightsh/shared_light_test.cpp).
constexpr float kCornerSpacing = 128.0f;
constexpr int kMaxCornerStep = 8;

int cornerStep(float cellSize) {
    return std::clamp(int(std::lround(kCornerSpacing / std::max(cellSize, 1.0f))), 1, kMaxCornerStep);
}

// The corner coordinates of an axis of `count` points: every `step`-th, and the last.
std::vector<int> cornerCoords(int count, int step) {
    std::vector<int> out;
    for (int c = 0; c < count - 1; c += step) out.push_back(c);
    out.push_back(std::max(0, count - 1));
    return out;
}

// What a block needs to know of one light at a corner point: whether its shadow ray was open,
// blocked or neither (partly transmitted, or no ray), and its light there (shadowed). Without
// -fast every light reaches every corner, so this is kept small: a directional contribution is
// projected again where it is shared, and only an emitter's integral (the costly projection) is
// kept, in floats.
enum class CornerRay : uint8_t { Open, Blocked, Other };
struct CornerLight {
    CornerRay ray = CornerRay::Other;
    int32_t integral = -1;  // index into CornerPoint::integrals, or -1: project color / direction again
    Vec3 color;             // already multiplied by the transmission
    Vec3 direction;
};

struct CornerPoint {
    bool free = false;
    Vec3 origin;
    int cluster = -1;
    std::vector<uint32_t> ids;        // the lights it holds, ascending (the blocks walk them in step)
    std::vector<CornerLight> lights;  // per id
    std::vector<std::array<float, sh::kCoeffCount * 3>> integrals;
};

struct Shared {
    const GridLattice& grid;
    std::span<const Light> lights;
    std::span<const uint8_t> leftOut;
    std::span<const float> envelopes;
    const LightingEnv& env;
    float margin;
    const BspTree* solidTree;
    const ShPointSink& sink;
    LightReach reach;
    std::array<std::vector<int>, 3> coords;       // corner coordinates per axis
    std::array<std::vector<uint8_t>, 3> isCorner;  // per axis and coordinate
    Progress& progress;
    std::atomic<uint64_t> sharedPairs{0};

    size_t index(int x, int y, int z) const {
        return size_t(x) + size_t(y) * size_t(grid.bounds[0]) + size_t(z) * size_t(grid.bounds[0]) * size_t(grid.bounds[1]);
    }
    Vec3 lattice(int x, int y, int z) const {
        return {grid.mins.x + float(x) * grid.size.x, grid.mins.y + float(y) * grid.size.y,
                grid.mins.z + float(z) * grid.size.z};
    }
    // The lattice box first..last grown by the nudge margin.
    Bounds box(std::array<int, 3> first, std::array<int, 3> last) const {
        return gridBlockBounds(GridBlock{first, {last[0] + 1, last[1] + 1, last[2] + 1}}, grid.mins, grid.size, margin);
    }
    // The style-0 lights not left out that may light a point of `box`.
    void select(const Bounds& box, std::vector<uint32_t>& candidates) const {
        gridLightsReaching(lights, reach, box, env.settings, candidates);
        std::erase_if(candidates, [&](uint32_t i) { return leftOut[i] || lights[i].style != 0; });
    }
    // Whether the rays of `light` from anywhere in `box` avoid structural solid (known to skip the walk).
    bool clearOfSolid(const Light& light, const Bounds& box) const {
        return solidTree && light.type != LightType::Sun && gridBoxToPointClear(*solidTree, box, light.origin);
    }
};

// Lights one corner point with every light that may reach it, keeps what the blocks around it
// need of each (CornerLight) and stores the point's own light.
void lightCorner(Shared& s, int x, int y, int z, CornerPoint& out) {
    const size_t index = s.index(x, y, z);
    out.ids.clear();
    out.lights.clear();
    out.integrals.clear();
    const std::optional<PlacedGridPoint> placed = s.sink.place(index, s.lattice(x, y, z));
    s.progress.advance(1);
    if (!placed) return;
    out.free = true;
    out.origin = placed->origin;
    out.cluster = placed->cluster;
    thread_local std::vector<uint32_t> candidates;
    thread_local std::vector<ShadowRay> rays;
    thread_local std::vector<int32_t> rayOf;
    thread_local std::vector<Vec3> transmission;
    // The lights that may reach the point itself: a light culled here gives it nothing, which is
    // what a block reading this corner takes a missing light for.
    s.select(s.box({x, y, z}, {x, y, z}), candidates);
    rays.clear();
    rayOf.clear();
    LightingEnv deferred = s.env;
    deferred.deferredRays = s.env.scene ? &rays : nullptr;
    for (size_t k = 0; k < candidates.size(); ++k) {
        const uint32_t i = candidates[k];
        const size_t before = rays.size();
        const std::optional<LightContribution> c =
            lightToGridPoint(s.lights[i], out.origin, out.cluster, deferred, s.envelopes[i]);
        if (!c) {
            rays.resize(before);
            continue;
        }
        out.ids.push_back(i);
        out.lights.push_back({CornerRay::Other, -1, c->color, c->direction});
        rayOf.push_back(rays.size() > before ? int32_t(before) : -1);
    }
    transmission.assign(rays.size(), Vec3{1, 1, 1});
    if (s.env.scene && !rays.empty()) s.env.scene->traceBatch(rays, transmission, false, false);
    sh::SH9Color sum;
    for (size_t k = 0; k < out.lights.size(); ++k) {
        CornerLight& c = out.lights[k];
        const Vec3 t = rayOf[k] >= 0 ? transmission[size_t(rayOf[k])] : Vec3{1, 1, 1};
        if (rayOf[k] >= 0)
            c.ray = t == Vec3{1, 1, 1} ? CornerRay::Open : t == Vec3{} ? CornerRay::Blocked : CornerRay::Other;
        c.color *= t;
        if (t == Vec3{}) continue;
        sh::SH9Color one;
        const Light& light = s.lights[out.ids[k]];
        if (projectContribution(one, light, out.origin, {c.color, c.direction, light.style}, t, s.env.settings, false)) {
            c.integral = int32_t(out.integrals.size());
            std::array<float, sh::kCoeffCount * 3>& kept = out.integrals.emplace_back();
            for (int j = 0; j < sh::kCoeffCount; ++j)
                for (int ch = 0; ch < 3; ++ch) kept[size_t(3 * j + ch)] = float(one.c[j][ch]);
        }
        sum = sh::add(sum, one);
    }
    s.sink.store(index, sum);
}

std::vector<CornerPoint> lightCornerPlane(Shared& s, int z) {
    const std::vector<int>& cx = s.coords[0];
    const std::vector<int>& cy = s.coords[1];
    std::vector<CornerPoint> plane(cx.size() * cy.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, plane.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t c = r.begin(); c != r.end(); ++c) lightCorner(s, cx[c % cx.size()], cy[c / cx.size()], z, plane[c]);
    });
    return plane;
}

// The points of one block that are not corner points, between corner coordinates lo and hi per
// axis (the last block of an axis owns its upper face too).
void lightBlock(Shared& s, std::array<size_t, 3> blockAt, const std::array<const CornerPoint*, 8>& slots) {
    std::array<int, 3> lo{}, hi{}, ownedEnd{};
    for (int a = 0; a < 3; ++a) {
        const std::vector<int>& c = s.coords[a];
        lo[a] = c[blockAt[a]];
        hi[a] = blockAt[a] + 1 < c.size() ? c[blockAt[a] + 1] : lo[a];
        ownedEnd[a] = blockAt[a] + 2 >= c.size() ? hi[a] + 1 : hi[a];
    }
    thread_local std::vector<size_t> index;
    thread_local std::vector<Vec3> origins;
    thread_local std::vector<int> clusters;
    thread_local std::vector<std::array<float, 3>> fractions;
    index.clear();
    origins.clear();
    clusters.clear();
    fractions.clear();
    uint64_t visited = 0;
    for (int z = lo[2]; z < ownedEnd[2]; ++z)
        for (int y = lo[1]; y < ownedEnd[1]; ++y)
            for (int x = lo[0]; x < ownedEnd[0]; ++x) {
                if (s.isCorner[0][size_t(x)] && s.isCorner[1][size_t(y)] && s.isCorner[2][size_t(z)]) continue;
                ++visited;
                const size_t i = s.index(x, y, z);
                const std::optional<PlacedGridPoint> placed = s.sink.place(i, s.lattice(x, y, z));
                if (!placed) continue;
                index.push_back(i);
                origins.push_back(placed->origin);
                clusters.push_back(placed->cluster);
                const std::array<int, 3> at{x, y, z};
                std::array<float, 3> t{};
                for (int a = 0; a < 3; ++a) t[a] = hi[a] > lo[a] ? float(at[a] - lo[a]) / float(hi[a] - lo[a]) : 0.0f;
                fractions.push_back(t);
            }
    s.progress.advance(visited);
    if (index.empty()) return;
    const size_t np = index.size();

    thread_local std::vector<uint32_t> candidates, withRays, withoutRays;
    thread_local std::vector<uint8_t> clearWithRays;
    // Only what reaches the placed points and the corners matters; every ray starts there too.
    Bounds placedBox;
    for (const Vec3& o : origins) placedBox.add(o);
    for (const CornerPoint* c : slots)
        if (c->free) placedBox.add(c->origin);
    s.select(placedBox, candidates);
    // The distinct corners (an axis one point thick folds its upper slots onto the lower ones).
    std::array<const CornerPoint*, 8> distinct{};
    std::array<size_t, 8> distinctOf{};  // per slot
    size_t cornerCount = 0;
    bool allFree = true;
    for (size_t slot = 0; slot < 8; ++slot) {
        const CornerPoint* c = slots[slot];
        const auto known = std::find(distinct.begin(), distinct.begin() + long(cornerCount), c);
        distinctOf[slot] = size_t(known - distinct.begin());
        if (known != distinct.begin() + long(cornerCount)) continue;
        distinct[cornerCount++] = c;
        allFree = allFree && c->free;
    }
    // Candidates ascend, and so does each corner's list: one cursor per corner finds them all.
    std::array<size_t, 8> cursor{};
    std::array<const CornerLight*, 8> found{};
    const bool share = allFree && s.env.scene;
    Bounds cornerBox;
    for (size_t k = 0; k < cornerCount; ++k) cornerBox.add(distinct[k]->origin);

    std::array<sh::SH9Color, 8> slotLight{};
    withRays.clear();
    withoutRays.clear();
    clearWithRays.clear();
    uint64_t skipped = 0;
    for (size_t k = 0; k < candidates.size(); ++k) {
        const uint32_t i = candidates[k];
        const Light& light = s.lights[i];
        if (share) {
            for (size_t c = 0; c < cornerCount; ++c) {
                const std::vector<uint32_t>& ids = distinct[c]->ids;
                while (cursor[c] < ids.size() && ids[cursor[c]] < i) ++cursor[c];
                found[c] = cursor[c] < ids.size() && ids[cursor[c]] == i ? &distinct[c]->lights[cursor[c]] : nullptr;
            }
            // Whether the corners agree (grid_sh_corners.h).
            bool open = true, blocked = true, seen = true;
            size_t reached = 0;
            for (size_t c = 0; c < cornerCount && seen && (open || blocked); ++c) {
                const CornerLight* at = found[c];
                if (!at) {
                    seen = !pvsCulled(light, distinct[c]->cluster, s.env);
                    continue;
                }
                ++reached;
                open = open && at->ray == CornerRay::Open;
                blocked = blocked && at->ray == CornerRay::Blocked;
            }
            const bool far = farFromBlock(light, cornerBox);
            const bool agree = seen && (open || blocked) && (far || reached == cornerCount);
            if (agree && far) {
                for (size_t slot = 0; slot < 8; ++slot) {
                    const CornerPoint& corner = *slots[slot];
                    const CornerLight* at = found[distinctOf[slot]];
                    if (!at || at->ray == CornerRay::Blocked) continue;
                    if (at->integral < 0) {
                        // Not an emitter's integral at the corner, so not here either: the
                        // transmission, which only tints an integral, is not needed.
                        projectContribution(slotLight[slot], light, corner.origin,
                                            {at->color, at->direction, light.style}, Vec3{1, 1, 1}, s.env.settings,
                                            false);
                        continue;
                    }
                    const std::array<float, sh::kCoeffCount * 3>& kept = corner.integrals[size_t(at->integral)];
                    for (int j = 0; j < sh::kCoeffCount; ++j)
                        for (int ch = 0; ch < 3; ++ch) slotLight[slot].c[j][ch] += double(kept[size_t(3 * j + ch)]);
                }
                skipped += np;
                continue;
            }
            if (agree && blocked) {
                skipped += np;
                continue;
            }
            if (agree) {  // near, open at every corner: lit at every point without rays
                withoutRays.push_back(i);
                continue;
            }
        }
        withRays.push_back(i);
        clearWithRays.push_back(s.clearOfSolid(light, placedBox) ? 1 : 0);
    }

    thread_local std::vector<sh::SH9Color> accs;
    accs.assign(np, sh::SH9Color{});
    addLightsToGridPointsSH(accs, s.lights, withRays, clearWithRays, s.envelopes, origins, clusters, s.env);
    if (!withoutRays.empty()) {
        LightingEnv unshadowed = s.env;
        unshadowed.scene = nullptr;
        addLightsToGridPointsSH(accs, s.lights, withoutRays, {}, s.envelopes, origins, clusters, unshadowed);
    }
    for (size_t p = 0; p < np; ++p) {
        if (share) {
            const std::array<float, 3>& t = fractions[p];
            for (size_t slot = 0; slot < 8; ++slot) {
                double w = 1;
                for (int a = 0; a < 3; ++a) w *= ((slot >> a) & 1) ? t[size_t(a)] : 1 - t[size_t(a)];
                if (w == 0) continue;
                for (int k = 0; k < sh::kCoeffCount; ++k)
                    for (int ch = 0; ch < 3; ++ch) accs[p].c[k][ch] += w * slotLight[slot].c[k][ch];
            }
        }
        s.sink.store(index[p], accs[p]);
    }
    s.sharedPairs += skipped;
}

}  // namespace

uint64_t traceGridSHSharedCorners(const GridLattice& grid, std::span<const Light> lights,
                                  std::span<const uint8_t> leftOut, std::span<const float> envelopes,
                                  const LightingEnv& env, float margin, const BspTree* solidTree, int threads,
                                  Progress& progress, const ShPointSink& sink) {
    if (grid.bounds[0] <= 0 || grid.bounds[1] <= 0 || grid.bounds[2] <= 0) return 0;
    Shared s{grid, lights, leftOut, envelopes, env, margin, solidTree, sink, LightReach(lights, envelopes), {}, {},
             progress};
    for (int a = 0; a < 3; ++a) {
        s.coords[size_t(a)] = cornerCoords(grid.bounds[size_t(a)], cornerStep(grid.size[a]));
        s.isCorner[size_t(a)].assign(size_t(grid.bounds[size_t(a)]), 0);
        for (int c : s.coords[size_t(a)]) s.isCorner[size_t(a)][size_t(c)] = 1;
    }
    const std::vector<int>& cz = s.coords[2];
    const size_t blocksX = std::max<size_t>(1, s.coords[0].size() - 1);
    const size_t blocksY = std::max<size_t>(1, s.coords[1].size() - 1);
    const size_t cornersX = s.coords[0].size();
    tbb::task_arena(threads > 0 ? threads : tbb::task_arena::automatic).execute([&] {
        std::vector<CornerPoint> lower = lightCornerPlane(s, cz[0]);
        const size_t slabs = std::max<size_t>(1, cz.size() - 1);
        for (size_t slab = 0; slab < slabs; ++slab) {
            std::vector<CornerPoint> upper;
            if (slab + 1 < cz.size()) upper = lightCornerPlane(s, cz[slab + 1]);
            const std::vector<CornerPoint>& top = slab + 1 < cz.size() ? upper : lower;
            tbb::parallel_for(tbb::blocked_range<size_t>(0, blocksX * blocksY, 1), [&](const tbb::blocked_range<size_t>& r) {
                for (size_t b = r.begin(); b != r.end(); ++b) {
                    const size_t bx = b % blocksX, by = b / blocksX;
                    std::array<const CornerPoint*, 8> slots{};
                    for (size_t slot = 0; slot < 8; ++slot) {
                        const size_t x = std::min(bx + (slot & 1), cornersX - 1);
                        const size_t y = std::min(by + ((slot >> 1) & 1), s.coords[1].size() - 1);
                        slots[slot] = &((slot >> 2) & 1 ? top : lower)[x + y * cornersX];
                    }
                    lightBlock(s, {bx, by, slab}, slots);
                }
            });
            if (slab + 1 < cz.size()) lower = std::move(upper);
        }
    });
    return s.sharedPairs.load();
}

}  // namespace q3::light
