// Conversions between BSP draw vertices and patch vertices, so that MST_PATCH surfaces of a BSP can
// be tessellated and meshes written back as draw vertices.
#pragma once

#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "bspfile.h"
#include "patch.h"

namespace q3::patch {

inline PatchVertex fromDrawVert(const bsp::DrawVert& dv) {
    PatchVertex v;
    v.xyz = Vec3::fromArray(dv.xyz);
    v.normal = Vec3::fromArray(dv.normal);
    v.st[0] = dv.st[0];
    v.st[1] = dv.st[1];
    v.lightmap[0] = dv.lightmap[0];
    v.lightmap[1] = dv.lightmap[1];
    for (int c = 0; c < 4; ++c) v.color[c] = dv.color[c];
    return v;
}

inline bsp::DrawVert toDrawVert(const PatchVertex& v) {
    bsp::DrawVert dv{};
    v.xyz.toArray(dv.xyz);
    v.normal.toArray(dv.normal);
    dv.st[0] = v.st[0];
    dv.st[1] = v.st[1];
    dv.lightmap[0] = v.lightmap[0];
    dv.lightmap[1] = v.lightmap[1];
    for (int c = 0; c < 4; ++c) {
        float value = std::round(v.color[c]);
        dv.color[c] = static_cast<uint8_t>(value < 0 ? 0 : (value > 255 ? 255 : value));
    }
    return dv;
}

// The control grid of an MST_PATCH surface: `verts` are its numVerts draw vertices (row-major,
// patchWidth per row). Throws std::invalid_argument when the sizes do not describe a valid grid.
inline ControlGrid gridFromDrawVerts(std::span<const bsp::DrawVert> verts, int width, int height) {
    ControlGrid grid;
    grid.width = width;
    grid.height = height;
    if (width < 3 || height < 3 || (width % 2) == 0 || (height % 2) == 0 ||
        verts.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("patch of " + std::to_string(width) + "x" + std::to_string(height) +
                                    " with " + std::to_string(verts.size()) + " vertices is not a valid control grid");
    grid.points.reserve(verts.size());
    for (const bsp::DrawVert& dv : verts) grid.points.push_back(fromDrawVert(dv));
    return grid;
}

}  // namespace q3::patch
