// Small scene builders shared by the light-stage tests.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "bspfile.h"
#include "lights.h"
#include "log.h"
#include "trace_scene.h"

namespace q3::light::test {

inline bsp::Entity entity(std::initializer_list<std::pair<const char*, const char*>> pairs) {
    bsp::Entity e;
    for (const auto& [k, v] : pairs) e.pairs.emplace_back(k, v);
    return e;
}

// Axis-aligned rectangle: `corner` plus the two edge vectors; texture coordinates 0..1.
inline SceneSurface quad(Vec3 corner, Vec3 edgeU, Vec3 edgeV, const LightingShader* shader = nullptr,
                         int skyIndex = -1) {
    SceneSurface s;
    s.shader = shader;
    s.skyIndex = skyIndex;
    s.xyz = {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
    s.st = {0, 0, 1, 0, 1, 1, 0, 1};
    s.triangles = {0, 1, 2, 0, 2, 3};
    return s;
}

// The area lights of a square emitter (2 * half on a side, at height h, facing +z or -z) of a
// surfacelight shader without backsplash.
inline std::vector<Light> squareEmitterLights(float surfaceLight, float half, float h, float facing) {
    LightingShader sh;
    sh.surfaceLight = surfaceLight;
    sh.backsplashFraction = 0;
    sh.backsplashSet = true;
    EmitterGeometry g;
    g.xyz = {{-half, -half, h}, {half, -half, h}, {half, half, h}, {-half, half, h}};
    g.normals.assign(4, Vec3{0, 0, facing});
    g.triangles = {0, 1, 2, 0, 2, 3};
    std::vector<Light> lights;
    appendAreaLights(lights, g, sh, {});
    return lights;
}

// A log that prints nothing and remembers every message.
struct CapturingLog {
    Log log{false};
    std::vector<std::string> warnings;
    CapturingLog() {
        log.addSink([this](LogLevel level, std::string_view text) {
            if (level == LogLevel::Warning) warnings.emplace_back(text);
        });
    }
};

}  // namespace q3::light::test
