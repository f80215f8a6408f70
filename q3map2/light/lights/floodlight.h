// Floodlight (q3map2 -floodlight, worldspawn _floodlight, shader q3map_floodLight): a "zero-effort"
// sky-like ambient. Each sample casts 64 rays (16 azimuths x 4 elevations within 88 degrees of its
// normal) of length `distance`; a ray that reaches nothing or sky counts 1, one that meets a surface
// counts distance_hit / distance; the mean (at most 1) times intensity times the normalised colour
// is added to the luxel, before dirt is applied.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bspfile.h"
#include "hit_scene.h"
#include "light_contribution.h"
#include "lightmap_filter.h"

namespace q3 {
struct ShaderFloodLight;
}

namespace q3::light {

struct FloodlightSettings {
    Vec3 color{0.94f, 0.94f, 1.0f};  // normalised so that its largest channel is 1
    float distance = 1024;
    float intensity = 128;
    float directionScale = 1;        // weight of the floodlight in a deluxemap's direction
    bool lowQuality = false;         // -lowquality: one ray in ten
};

// Largest channel scaled to 1 (q3map2 ColorNormalize); black stays black.
Vec3 normalizeFloodColor(Vec3 color);

// The global floodlight: -floodlight enables it with the defaults; worldspawn _floodlight
// "r g b distance intensity directionScale" enables it and overrides them (q3map2 SetupFloodLight:
// a black colour means the default, distance < 1 -> 1024, intensity < 1 -> 128, scale < 0 -> 1).
// nullopt when neither is given. Throws CompileError (naming `fileName`) on a malformed value.
std::optional<FloodlightSettings> globalFloodlight(bool option, bool lowQuality, const bsp::Entity& worldspawn,
                                                   const std::string& fileName);

// A shader's q3map_floodLight; nullopt when it has none or its intensity is 0.
std::optional<FloodlightSettings> shaderFloodlight(const std::optional<ShaderFloodLight>& directive);

// Fraction 0..1 of open surroundings seen by one sample.
float floodlightForSample(Vec3 origin, Vec3 normal, const HitScene& scene, const FloodlightSettings& settings);

// Floodlight colour of every luxel of a raw lightmap (row-major `points`; nullopt = unmapped gets 0).
std::vector<Vec3> floodlightForLightmap(const std::vector<std::optional<SamplePoint>>& points,
                                        const HitScene& scene, const FloodlightSettings& settings);

// Adds `flood` to every mapped luxel.
void addFloodlight(LuxelImage& image, const std::vector<Vec3>& flood);

}  // namespace q3::light
