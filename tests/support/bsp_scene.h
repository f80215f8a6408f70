// Building blocks of the small BSP scenes tests write themselves (header-only: only the tests
// that link the bspfile library include it).
#pragma once

#include <cstdint>

#include "bspfile.h"
#include "vec3.h"

namespace q3::test {

// Appends a planar quad (corner + two edges) using `shader`; its normal is cross(edgeV, edgeU),
// Quake's clockwise order. Texture coordinates run 0..1 over the quad, vertex colours are white.
inline void addQuad(bsp::Bsp& b, Vec3 corner, Vec3 edgeU, Vec3 edgeV, int shader) {
    const Vec3 normal = normalize(cross(edgeV, edgeU));
    bsp::Surface s{};
    s.shaderNum = shader;
    s.fogNum = -1;
    s.surfaceType = bsp::MST_PLANAR;
    s.firstVert = static_cast<int32_t>(b.drawVerts.size());
    s.numVerts = 4;
    s.firstIndex = static_cast<int32_t>(b.drawIndexes.size());
    s.numIndexes = 6;
    s.lightmapNum = 0;
    normal.toArray(s.lightmapVecs[2]);
    const Vec3 corners[4] = {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
    const float st[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        bsp::DrawVert v{};
        corners[i].toArray(v.xyz);
        v.st[0] = st[i][0];
        v.st[1] = st[i][1];
        normal.toArray(v.normal);
        v.color[0] = v.color[1] = v.color[2] = v.color[3] = 255;
        b.drawVerts.push_back(v);
    }
    for (int32_t idx : {0, 2, 1, 0, 3, 2}) b.drawIndexes.push_back(idx);
    b.surfaces.push_back(s);
}

}  // namespace q3::test
