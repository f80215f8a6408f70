// The world lights lump (BSPX "WORLDLIGHTS"): the point, spot and sun lights of a map, one fixed
// 96-byte little-endian record each after a 16-byte header, so that a runtime can light moving
// models with the strongest of them directly. See docs/world-lights-format.md.
// Dependency-free: engines can take this header and its .cpp files as they are.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace q3::sh {

constexpr const char* kWorldLightsLumpName = "WORLDLIGHTS";
constexpr uint32_t kWorldLightsVersion = 1;
constexpr size_t kWorldLightsHeaderBytes = 16;
constexpr size_t kWorldLightRecordBytes = 96;

enum class WorldLightType : uint32_t { Point = 0, Spot = 1, Sun = 2 };

// How the light fades with distance. Suns, and only suns, are Parallel.
enum class WorldLightFalloff : uint32_t {
    InverseSquare = 0,  // q3map2's default: 1 / D^2
    Linear = 1,         // q3map2's linear lights (spawnflags 1, -wolf): 1 - D * rate
    Controlled = 2,     // the controlled model (brightness, falloff_start/end_dist, curvature)
    Parallel = 3,       // no falloff
};

// flags
constexpr uint32_t kWorldLightInShGrid = 1u;  // its direct light is already in the SH grid
constexpr uint32_t kWorldLightKnownFlags = kWorldLightInShGrid;

struct WorldLight {
    WorldLightType type = WorldLightType::Point;
    WorldLightFalloff falloff = WorldLightFalloff::InverseSquare;
    uint32_t flags = 0;
    int32_t style = 0;
    int32_t cluster = -1;                    // BSP cluster of the origin, -1 for suns
    std::array<float, 3> origin{};
    std::array<float, 3> intensity{};        // RGB, SH grid units (see the format document)
    std::array<float, 3> direction{};        // spot: unit axis away from the light; sun: unit, towards the sun
    // InverseSquare and Linear: {minimum distance, extra distance, cutoff, rate (Linear)};
    // Controlled: {start, end, curvature, 0}; Parallel: all 0.
    std::array<float, 4> falloffConstants{};
    // Spots, q3map2 model: {radius per unit of distance along the axis, fade width, 0, 0};
    // spots, controlled model: {inner half angle, outer half angle (degrees), spherical ambient, 0};
    // others: all 0.
    std::array<float, 4> cone{};
    float incidenceWeight = 1;  // w of (1 - w) + w * n.l for n.l > 0 (1: Lambert)
    float radius = 0;           // no light beyond this distance; 0: no end (suns, unbounded lights)
};

// One line saying what is wrong with a lump image ("WORLDLIGHTS: ..."), or an empty string.
std::string checkWorldLightsLump(const uint8_t* data, size_t size);
// Decodes a lump image (checked first). Returns false and sets `error` (one line) when invalid.
bool decodeWorldLights(const uint8_t* data, size_t size, std::vector<WorldLight>& out, std::string& error);
// The lump image of `lights`, in their order.
std::vector<uint8_t> encodeWorldLights(std::span<const WorldLight> lights);
// What is wrong with one record (no lump name, no index), or an empty string.
std::string checkWorldLight(const WorldLight& light);

// Constants of the evaluation formulas, shared with the generated GLSL (world_lights_glsl.h).
constexpr float kControlledSquareStart = 16.0f;  // the controlled model's 1/d^2 part starts at q3map2's clamp
constexpr float kDegreesPerRadian = 180.0f / 3.14159265358979323846f;

// The controlled model's distance falloff and spot cone (light-models.md; angles in degrees, half
// the full cone angles), shared with the compiler so that both compute them alike.
float controlledFalloffFactor(float distance, float start, float end, float curvature);
float controlledConeFactor(float cosAngle, float innerHalfAngle, float outerHalfAngle, float sphericalAmbient);

// Unoccluded irradiance of `light` at `point` on a surface with unit normal `normal`, in SH grid
// units: the formula of the format document, the direct light the SH grid projects at that point.
std::array<float, 3> evaluateWorldLight(const WorldLight& light, const std::array<float, 3>& point,
                                        const std::array<float, 3>& normal);
// The same without the incidence term (what reaches the point from the light's direction).
std::array<float, 3> worldLightArriving(const WorldLight& light, const std::array<float, 3>& point);

}  // namespace q3::sh
