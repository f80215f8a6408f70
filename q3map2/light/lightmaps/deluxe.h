// Deluxe maps (-deluxe): beside every lightmap page, a page of the same size holding, per texel,
// the main direction the style-0 light comes from, encoded as dir * 127.5 + 127.5. Pages are
// interleaved in lump 14 (light 0, direction 0, light 1, direction 1, ...) so every surface's
// lightmapNum is even: that is how ioquake3's renderergl2 and DarkPlaces recognise deluxe maps.
// Worldspawn gets "deluxeMaps" 1 (-deluxemode 0, model space) or 2 (-deluxemode 1, tangent space).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "bspfile.h"
#include "color_pipeline.h"
#include "vec3.h"

namespace q3::light {

struct LightContext;
struct LightmapBlock;
struct PackedLightmaps;
struct SurfaceLight;

struct DeluxeSettings {
    bool tangentSpace = false;  // -deluxemode 1
};

// nullopt unless -deluxe is on.
std::optional<DeluxeSettings> deluxeSettings(const LightContext& ctx);

// Tangent frame of a surface from its draw vertices: unit s and t directions of its texture
// (zero vectors for degenerate mappings).
struct TangentFrame {
    Vec3 tangent, bitangent;
};
TangentFrame surfaceTangentFrame(const bsp::Bsp& bsp, int surfaceNum);

// Direction `dir` (unit, model space) in the tangent space of a luxel with unit normal `n`.
Vec3 toTangentSpace(Vec3 dir, Vec3 n, const TangentFrame& frame);
// One texel: normalize(dir) * 127.5 + 127.5 per axis; a zero direction stores `fallback`.
Rgb8 encodeDirection(Vec3 dir, Vec3 fallback);

// The direction texels of one lit surface (per BSP luxel; no light: the luxel normal, or +Z in
// tangent space).
std::vector<Rgb8> encodeDeluxels(const bsp::Bsp& bsp, const SurfaceLight& lit, const DeluxeSettings& settings);

// Turns the packed light pages [L0, L1, ...] into [L0, D0, L1, D1, ...]: each block's direction
// texels are stamped at its placement in the direction page after its light page, and every
// placement's page index is doubled (a solid block's one texel takes its first texel's direction).
// Blocks must not be twins of others.
void interleaveDirectionPages(PackedLightmaps& packed, std::span<const LightmapBlock> blocks);

// Worldspawn "deluxeMaps" key for the mode.
void markDeluxeWorldspawn(bsp::Entity& worldspawn, const DeluxeSettings& settings);

}  // namespace q3::light
