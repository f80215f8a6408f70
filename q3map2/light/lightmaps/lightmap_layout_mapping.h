// Which super luxels of a raw lightmap a surface maps, and where each one samples light, following
// q3map2's MapRawLightmap: the surface's vertices and the midpoints of a recursive split of its
// triangles (or patch quads) until every edge is at most one super luxel long are dropped into the
// luxel grid (a point at lightmap coordinate s belongs to luxel floor(s), so a vertex lying exactly
// on a luxel's upper border maps the next luxel). The first point to reach a luxel decides its
// sample point; every point adds its normal to the luxel's normal.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "lightmap_layout.h"

namespace q3::light {

// A surface point in super-luxel lightmap coordinates with its world position and normal.
struct MapVertex {
    std::array<float, 2> st;
    Vec3 xyz;
    Vec3 normal;
};

// One surface to map: triangles (index triples), or a quadWidth x quadHeight vertex mesh mapped
// quad by quad as q3map2 maps patches (a quad that is not flat falls back to its two triangles).
struct MappingSurface {
    std::vector<MapVertex> verts;
    std::vector<uint32_t> triangles;
    int quadWidth = 0, quadHeight = 0;
};

// Fills lm.luxels (lm.luxels' size, origin, vecs, plane, axis and sample offset must be set).
void mapSurfacesOntoLuxels(RawLightmap& lm, std::span<const MappingSurface> surfaces);

}  // namespace q3::light
