#include "large_bsp.h"

#include <cstdio>
#include <cstring>
#include <random>
#include <string>

namespace q3::test {

bsp::Bsp makeLargeBsp(uint32_t seed) {
    constexpr size_t kLightmapPages = 160;
    constexpr size_t kVertices = 100000;
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> coordinate(-4096.0f, 4096.0f);

    bsp::Bsp b;
    b.entities = "{\n\"classname\" \"worldspawn\"\n\"message\" \"crash safety " + std::to_string(seed) + "\"\n}\n";
    b.entities.push_back('\0');
    for (int i = 0; i < 4; ++i) {
        bsp::Shader shader{};
        std::snprintf(shader.name, sizeof shader.name, "textures/crash/s%u_%d", seed, i);
        shader.contentFlags = 1;
        b.shaders.push_back(shader);
    }
    for (int axis = 0; axis < 3; ++axis) {
        bsp::Plane plane{};
        plane.normal[axis] = 1.0f;
        plane.dist = float(seed % 1000) + float(axis);
        b.planes.push_back(plane);
    }
    b.lightmaps.resize(kLightmapPages * bsp::kLightmapPageBytes);
    for (uint8_t& byte : b.lightmaps) byte = static_cast<uint8_t>(random());
    b.drawVerts.resize(kVertices);
    for (bsp::DrawVert& v : b.drawVerts) {
        for (float& x : v.xyz) x = coordinate(random);
        v.normal[2] = 1.0f;
        std::memset(v.color, 255, sizeof v.color);
    }
    return b;
}

}  // namespace q3::test
