// -shgather: the indirect light of every SH probe, gathered from the lit map after the lightmaps.
// Each probe traces a fixed set of directions (spherical Fibonacci, equal solid angle 4 pi / N)
// to the nearest surface; what a ray brings back is the surface's reflected light, i.e. its baked
// light (lightmap luxel at the hit, or vertex colour for vertex-lit surfaces) times its albedo (the
// texel of its image at the hit) over pi. The samples are projected onto L2 SH radiance, convolved
// to irradiance and added to the probe.
//
// Split between direct and indirect (docs/sh-for-mappers.md): TraceGridSH already holds every
// light source seen from the probe (point, spot and sun lights, sky light, surface lights), so
// the gather leaves out what a ray would see of them: emission of surface-light shaders and the
// sky add nothing here. Only light that has been reflected once by a surface is gathered, so
// nothing is counted twice.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "lights.h"
#include "sh.h"
#include "sh_grid_lump.h"
#include "vec3.h"

namespace q3 {
class Log;
}

namespace q3::light {

struct ShTraceStats;

struct LightContext;
struct ShGridLayout;

// The linear light of one lightmapped surface as baked by lightLightmaps (BSP luxels, legacy units
// 0..255+, before the colour pipeline), with the luxel coordinate of each of its draw vertices.
struct BakedSurfaceLight {
    int width = 0, height = 0;  // 0 = not lightmapped
    std::vector<Vec3> color;
    std::vector<std::array<float, 2>> vertexCoords;
};

// What a ray that hits a surface of a shader reflects: its texture image (nullptr: the average
// is used) and the image's average colour, both 0..1.
struct ShaderAlbedo {
    const LightImage* image = nullptr;
    Vec3 average{0.5f, 0.5f, 0.5f};
};

// The albedo of every BSP shader: the first image of the shader's light-image candidates that
// loads (editor image, then the shader name), texel colour / 255. Shaders without an image get
// 0.5 grey. `images` owns the images decoded here; those the lighting shaders hold already
// (ctx.shaders.images) are pointed at, not decoded again.
std::vector<ShaderAlbedo> loadShaderAlbedo(const LightContext& ctx, std::vector<LightImage>& images, Log& log);

// The shader albedo of a run, loaded by the first step that needs it (-bounce, -shgather) and kept
// in the context for the others.
struct ShaderAlbedoSet {
    std::vector<LightImage> images;     // owned texture images
    std::vector<ShaderAlbedo> shaders;  // per BSP shader, pointing into `images`
};
const std::vector<ShaderAlbedo>& shaderAlbedo(LightContext& ctx, Log& log);

// N unit directions of a spherical Fibonacci set: equal-area cells, deterministic.
std::vector<Vec3> gatherDirections(int count);

struct ShGatherStats {
    uint64_t probes = 0;        // probes that traced rays
    uint64_t interpolated = 0;  // probes that took the trilinear mean of coarse probes (-shgatherstep)
    uint64_t rays = 0;
    double seconds = 0;
};

// Adds the gathered indirect irradiance (times -gridscale) to every point of `grid` not marked in
// `solid`, then refills the points in solid from their neighbours (as TraceGridSH does). With
// -shgatherstep S > 1 only the probes whose indices are multiples of S gather; the others take the
// trilinear mean of the coarse probes around them (and gather themselves when one of those is in
// solid or past the grid). Parallel over probes; each probe sums its own rays in a fixed order and
// interpolation reads only coarse results, so the result does not depend on the thread count.
// `traced` holds where TraceGridSH lit each probe (ShTraceStats::solid and ::origins).
ShGatherStats gatherIndirectSH(const LightContext& ctx, std::span<const ShaderAlbedo> albedo, sh::GridLumpImage& grid,
                               const ShTraceStats& traced, Log& log);

// The indirect SH irradiance at one point (no -gridscale), exposed for tests and measurements.
class GatherScene;
sh::SH9Color gatherProbe(const GatherScene& scene, Vec3 origin, std::span<const Vec3> directions);

// The closest-hit scene of the gather: every drawn surface of ctx.surfaces (sky included, as a
// surface that reflects nothing), with what a hit needs to know.
class GatherScene {
public:
    GatherScene(const LightContext& ctx, std::span<const ShaderAlbedo> albedo);
    ~GatherScene();
    GatherScene(const GatherScene&) = delete;
    GatherScene& operator=(const GatherScene&) = delete;

    // Radiance (SH units: 1.0 = legacy 255, per steradian) reflected towards `origin` by the
    // nearest surface along `direction`; zero when the ray escapes or hits sky. Emitting surfaces
    // send only the light they reflect, never their emission (that is direct light).
    sh::Rgb radianceAlong(Vec3 origin, Vec3 direction) const;
    // The same for many directions from one origin (out[i] for directions[i]), traced in packets.
    void radianceAlong(Vec3 origin, std::span<const Vec3> directions, std::span<sh::Rgb> out) const;
    // clear[k] = no surface lies between `a` and targets[k] (at most 8 targets; probes that may
    // share their light), traced as one packet.
    void clearTo(Vec3 a, std::span<const Vec3> targets, std::span<uint8_t> clear) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace q3::light
