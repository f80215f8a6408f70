// Valid WORLDLIGHTS records of every type and falloff model, for the codec, JSON, -info and fuzz
// tests.
#pragma once

#include <vector>

#include "world_lights.h"

namespace q3::sh::test {

inline std::vector<WorldLight> sampleWorldLights() {
    std::vector<WorldLight> out;
    WorldLight point;
    point.origin = {128.5f, -64.25f, 96};
    point.intensity = {2.5f, 1.25f, 0.1f};
    point.falloffConstants = {16, 0, 1e-5f, 0};
    point.radius = 700;
    point.cluster = 3;
    point.flags = kWorldLightInShGrid;
    out.push_back(point);

    WorldLight linear = point;
    linear.falloff = WorldLightFalloff::Linear;
    linear.falloffConstants = {16, 8, 0, 0.0025f};
    linear.style = 5;
    linear.flags = 0;
    linear.radius = 0;
    out.push_back(linear);

    WorldLight spot;
    spot.type = WorldLightType::Spot;
    spot.origin = {0, 0, 200};
    spot.intensity = {40, 40, 30};
    spot.direction = {0, 0, -1};
    spot.falloffConstants = {16, 0, 0, 0};
    spot.cone = {0.4f, 32, 0, 0};
    spot.cluster = 0;
    out.push_back(spot);

    WorldLight controlled;
    controlled.type = WorldLightType::Spot;
    controlled.falloff = WorldLightFalloff::Controlled;
    controlled.origin = {-300, 20, 50};
    controlled.intensity = {0.8f, 0.4f, -0.2f};
    controlled.direction = {0.6f, 0.8f, 0};
    controlled.falloffConstants = {32, 400, 0.5f, 0};
    controlled.cone = {22.5f, 30, 0.1f, 0};
    controlled.incidenceWeight = 0.5f;
    controlled.radius = 400;
    controlled.cluster = 7;
    out.push_back(controlled);

    WorldLight sun;
    sun.type = WorldLightType::Sun;
    sun.falloff = WorldLightFalloff::Parallel;
    sun.intensity = {0.9f, 0.85f, 0.7f};
    sun.direction = {0, 0.6f, 0.8f};
    sun.flags = kWorldLightInShGrid;
    out.push_back(sun);
    return out;
}

}  // namespace q3::sh::test
