// Builders of small emitting surfaces for the bounce emitter tests.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "bounce_lights.h"

namespace q3::light::test {

// An axis-aligned square in the z = 0 plane from (0, 0) to (size, size), facing +z, split into the
// two triangles (0,1,2) and (0,2,3). The texture repeats once over it (st = xy / size) and its
// lightmap of lmSize x lmSize luxels covers it exactly (lm = xy / size * lmSize), every luxel
// `luxel` until `luxelAt` (lightmap x, y) says otherwise; every vertex's light is `luxel` too.
inline BounceSurface squareSurface(float size, int lmSize, Vec3 luxel,
                                   const std::function<Vec3(int, int)>& luxelAt = nullptr) {
    BounceSurface s;
    s.surfaceNum = 0;
    const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& c : corners) {
        BounceVertex v;
        v.xyz = {c[0] * size, c[1] * size, 0};
        v.normal = {0, 0, 1};
        v.st = {c[0], c[1]};
        v.lm = {c[0] * static_cast<float>(lmSize), c[1] * static_cast<float>(lmSize)};
        s.verts.push_back(v);
        s.vertexLight.push_back(luxel);
    }
    s.triangles = {0, 1, 2, 0, 2, 3};
    s.width = lmSize;
    s.height = lmSize;
    s.luxels.resize(static_cast<size_t>(lmSize) * static_cast<size_t>(lmSize), luxel);
    if (luxelAt)
        for (int y = 0; y < lmSize; ++y)
            for (int x = 0; x < lmSize; ++x) s.luxels[static_cast<size_t>(y * lmSize + x)] = luxelAt(x, y);
    return s;
}

// Moves every vertex of `s` by `offset`.
inline void translate(BounceSurface& s, Vec3 offset) {
    for (BounceVertex& v : s.verts) v.xyz += offset;
}

// Sets every vertex's texture coordinate to `st` (one texel colours the whole surface).
inline void setUniformSt(BounceSurface& s, float sCoord, float tCoord) {
    for (BounceVertex& v : s.verts) v.st = {sCoord, tCoord};
}

inline Bounds lightBounds(const Light& light) {
    Bounds b;
    for (const Vec3& p : light.winding) b.add(p);
    return b;
}

inline float polygonArea(const std::vector<Vec3>& w) {
    float area = 0;
    for (size_t i = 2; i < w.size(); ++i) area += 0.5f * length(cross(w[i - 1] - w[0], w[i] - w[0]));
    return area;
}

}  // namespace q3::light::test
