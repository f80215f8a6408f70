#include "dirt.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "light_random.h"

namespace q3::light {

namespace {
constexpr int kDirtAzimuthSteps = 16;
constexpr int kDirtElevationSteps = 3;
constexpr float kDirtConeDegrees = 88;
// How far beyond a sky surface the solid behind it may begin (the two coincide on sealed maps).
constexpr float kSkyEntrySlack = 1.0f;
static_assert(kDirtSkyReach > kSkyEntrySlack + 0.5f, "the sky bound must cover the probe's length");
}  // namespace

DirtSettings dirtSettingsFromOptions(const LightOptions& options) {
    DirtSettings s;
    s.mode = options.dirtMode;
    s.depth = options.dirtDepth;
    s.scale = options.dirtScale;
    s.gain = options.dirtGain;
    s.debug = options.dirtDebug;
    return s;
}

const std::vector<Vec3>& dirtConeDirections() {
    static const std::vector<Vec3> directions =
        coneDirections(kDirtAzimuthSteps, kDirtElevationSteps, kDirtConeDegrees);
    return directions;
}

uint64_t dirtSeed(Vec3 origin) {
    uint32_t bits[3];
    std::memcpy(&bits[0], &origin.x, 4);
    std::memcpy(&bits[1], &origin.y, 4);
    std::memcpy(&bits[2], &origin.z, 4);
    SplitMix mix((uint64_t{bits[0]} << 32) ^ (uint64_t{bits[1]} << 16) ^ bits[2] ^ 0xD1B54A32D192ED03ull);
    return mix.next();
}

SolidBackedTest dirtSolidBacked(const BspTree& tree) {
    constexpr float kBehind = 0.5f;
    return [&tree](std::span<const Vec3, 3> t) {
        const Vec3 back = cross(t[1] - t[0], t[2] - t[0]);  // clockwise from the front: points behind
        const float area = length(back);
        if (!(area > 1e-6f) || !std::isfinite(area)) return false;
        const Vec3 shift = back * (kBehind / area);
        const std::array<Vec3, 3> behind{t[0] + shift, t[1] + shift, t[2] + shift};
        return tree.polygonInSolid(behind);
    };
}

float dirtForSample(Vec3 origin, Vec3 normal, const HitScene& scene, const DirtSettings& settings, uint64_t seed,
                    float ignoreNear, const BspTree* tree, bool skyNear) {
    Vec3 right, up;
    tangentFrame(normal, right, up);
    const float depth = settings.depth;
    const std::vector<Vec3>& cone = dirtConeDirections();
    constexpr size_t kMaxRays = size_t(kDirtAzimuthSteps * kDirtElevationSteps) + 1;
    std::array<Vec3, kMaxRays> directions;
    size_t count = 0;
    if (settings.mode == 1) {
        SplitMix random(seed);
        for (size_t i = 0; i < cone.size(); ++i) {
            const float azimuth = random.unit() * degToRad(360.0f);
            const float elevation = random.unit() * degToRad(kDirtConeDegrees);
            const Vec3 local{std::cos(azimuth) * std::sin(elevation), std::sin(azimuth) * std::sin(elevation),
                             std::cos(elevation)};
            directions[count++] = toFrame(local, right, up, normal);
        }
    } else {
        for (const Vec3& local : cone) directions[count++] = toFrame(local, right, up, normal);
    }
    directions[count++] = normal;

    // A ray that enters structural solid stops where it enters, however close (the inhibit radius
    // only skips surfaces), and before any nearer detail surface it may cross. So the solid is
    // walked first; the nearest surface matters to such a ray only when it is a sky face no farther
    // than the entry (sky faces seal the world with solid behind them: rays that reach sky do not
    // darken), which the sky surfaces alone can rule out.
    std::array<float, kMaxRays> entry;  // distance to the solid, or -1
    entry.fill(-1.0f);
    std::array<Vec3, kMaxRays> solidDirections;
    std::array<float, kMaxRays> skyReach;
    std::array<size_t, kMaxRays> solidRay;
    size_t solidCount = 0;
    std::array<std::optional<Vec3>, kMaxRays> solids;
    if (tree) tree->segmentSolidEntries(origin, std::span(directions.data(), count), depth, solids);
    for (size_t i = 0; i < count; ++i)
        if (const std::optional<Vec3>& solid = solids[i]) {
            entry[i] = length(*solid - origin);
            solidDirections[solidCount] = directions[i];
            // A little past the entry and its slack: a sky face beyond it only costs a nearest query.
            skyReach[solidCount] = (entry[i] + kSkyEntrySlack) * 1.001f + 0.01f;
            solidRay[solidCount++] = i;
        }
    std::array<uint8_t, kMaxRays> skyBeforeSolid{};
    std::array<uint8_t, kMaxRays> needsNearest{};
    if (solidCount > 0 && skyNear) {
        scene.skyAlongMany(origin, std::span(solidDirections.data(), solidCount), ignoreNear,
                           std::span(skyReach.data(), solidCount), std::span(skyBeforeSolid.data(), solidCount));
        for (size_t k = 0; k < solidCount; ++k) needsNearest[solidRay[k]] = skyBeforeSolid[k];
    }
    // Rays the walk found open can meet only surfaces with no solid right behind them (the scene's
    // open part); rays with a sky face before their entry take the whole scene.
    std::array<RayHit, kMaxRays> hits{};
    for (const bool open : {true, false}) {
        if (!open && solidCount == 0) break;
        std::array<Vec3, kMaxRays> queried;
        std::array<size_t, kMaxRays> queriedRay;
        size_t queriedCount = 0;
        for (size_t i = 0; i < count; ++i)
            if (open ? entry[i] < 0 : needsNearest[i] != 0) {
                queried[queriedCount] = directions[i];
                queriedRay[queriedCount++] = i;
            }
        if (queriedCount == 0) continue;
        std::array<RayHit, kMaxRays> queriedHits;
        const std::span<const Vec3> rays(queried.data(), queriedCount);
        const std::span<RayHit> answers(queriedHits.data(), queriedCount);
        if (open && tree)
            scene.nearestOpenMany(origin, rays, ignoreNear, depth, answers);
        else
            scene.nearestMany(origin, rays, ignoreNear, depth, answers);
        for (size_t k = 0; k < queriedCount; ++k) hits[queriedRay[k]] = queriedHits[k];
    }

    float gathered = 0;
    for (size_t i = 0; i < count; ++i) {
        const RayHit& hit = hits[i];
        if (entry[i] >= 0) {
            const bool sky = hit.hit && hit.sky && hit.distance <= entry[i] + kSkyEntrySlack;
            if (!sky) gathered += 1.0f - entry[i] / depth;
        } else if (hit.hit && !hit.sky) {
            gathered += 1.0f - hit.distance / depth;
        }
    }
    if (gathered <= 0) return 1.0f;
    float dirt = std::min(1.0f, std::pow(gathered / static_cast<float>(cone.size() + 1), settings.gain));
    dirt = std::min(1.0f, dirt * settings.scale);
    return 1.0f - dirt;
}

namespace {
// The sky boxes among `candidates` (all when null) that come within `reach` of `box`, grown well
// past the rounding of ray ends at map scale: no ray from inside `box` meets the others' sky.
void skyBoxesWithin(std::span<const Bounds> skies, const std::vector<uint32_t>* candidates, const Bounds& box,
                    float reach, std::vector<uint32_t>& out) {
    const Vec3 grown = Vec3::splat(reach * 1.001f + 0.1f);
    const Bounds reached{box.mins - grown, box.maxs + grown};
    out.clear();
    auto test = [&](uint32_t id) {
        if (!skies[id].empty() && skies[id].intersects(reached)) out.push_back(id);
    };
    if (candidates)
        for (uint32_t id : *candidates) test(id);
    else
        for (uint32_t id = 0; id < skies.size(); ++id) test(id);
}
}  // namespace

std::vector<float> dirtForLightmap(const std::vector<std::optional<SamplePoint>>& points, int width, int height,
                                   const HitScene& scene, const DirtSettings& settings, bool noDirty,
                                   const BspTree* tree, std::span<const uint8_t> wanted) {
    const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height);
    std::vector<float> raw(count, 0.0f);
    auto isWanted = [&](size_t i) { return wanted.empty() || (i < wanted.size() && wanted[i] != 0); };
    // Whether sky lies within reach is asked of the lightmap, then of blocks of its luxels: most
    // blocks have none near (asking each sample as well spares nothing more on oacmpdm5).
    const std::span<const Bounds> skies = scene.skyTriangleBoxes();
    const float skyReach = settings.depth + kDirtSkyReach;
    auto at = [width](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(width) + size_t(x); };
    Bounds lightmapBox;
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i] && isWanted(i)) lightmapBox.add(points[i]->origin);
    std::vector<uint32_t> lightmapSkies, blockSkies;
    if (!noDirty && !lightmapBox.empty()) skyBoxesWithin(skies, nullptr, lightmapBox, skyReach, lightmapSkies);
    constexpr int kBlock = 8;
    for (int by = 0; by < height; by += kBlock)
        for (int bx = 0; bx < width; bx += kBlock) {
            const int ex = std::min(width, bx + kBlock), ey = std::min(height, by + kBlock);
            blockSkies.clear();
            if (!lightmapSkies.empty()) {
                Bounds box;
                for (int y = by; y < ey; ++y)
                    for (int x = bx; x < ex; ++x)
                        if (at(x, y) < points.size() && points[at(x, y)] && isWanted(at(x, y)))
                            box.add(points[at(x, y)]->origin);
                if (!box.empty()) skyBoxesWithin(skies, &lightmapSkies, box, skyReach, blockSkies);
            }
            for (int y = by; y < ey; ++y)
                for (int x = bx; x < ex; ++x) {
                    const size_t i = at(x, y);
                    if (i >= points.size() || !points[i]) continue;
                    if (noDirty || !isWanted(i)) {
                        raw[i] = 1.0f;
                        continue;
                    }
                    const Vec3 origin = points[i]->origin;
                    raw[i] = dirtForSample(origin, points[i]->normal, scene, settings, dirtSeed(origin),
                                           kDirtInhibitRadius, tree, !blockSkies.empty());
                }
        }
    // Smoothing reads the unsmoothed factors (q3map2 smooths in place, so its result depends on
    // the scan order; reading a copy keeps the 3x3 mean symmetric).
    std::vector<float> smoothed = raw;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
            if (!points[i]) continue;
            float sum = raw[i], samples = 1;
            for (int sy = y - 1; sy <= y + 1; ++sy)
                for (int sx = x - 1; sx <= x + 1; ++sx) {
                    if (sx < 0 || sy < 0 || sx >= width || sy >= height || (sx == x && sy == y)) continue;
                    const size_t j = static_cast<size_t>(sy) * static_cast<size_t>(width) + static_cast<size_t>(sx);
                    if (!points[j] || raw[j] <= 0) continue;
                    sum += raw[j];
                    samples += 1;
                }
            smoothed[i] = sum / samples;
        }
    return smoothed;
}

std::vector<uint8_t> dirtWantedLuxels(const LuxelImage& image) {
    const int w = image.width, h = image.height;
    std::vector<uint8_t> wanted(image.color.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (image.color[image.index(x, y)] == Vec3{}) continue;
            for (int sy = std::max(0, y - 1); sy <= std::min(h - 1, y + 1); ++sy)
                for (int sx = std::max(0, x - 1); sx <= std::min(w - 1, x + 1); ++sx) wanted[image.index(sx, sy)] = 1;
        }
    return wanted;
}

void applyDirt(LuxelImage& image, const std::vector<float>& dirt, bool debug) {
    for (size_t i = 0; i < image.color.size() && i < dirt.size(); ++i) {
        if (image.state[i] != LuxelState::Mapped) continue;
        image.color[i] = debug ? Vec3::splat(dirt[i] * 255.0f) : image.color[i] * dirt[i];
    }
}

}  // namespace q3::light
