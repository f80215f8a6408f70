// Meta triangles merged into surfaces (q3map2 surface_meta.cpp MergeMetaTriangles,
// MetaTrianglesToSurface, AddMetaTriangleToSurface). Triangles are sorted by shader, fog, entity,
// shadow flags and sample size, then by their lowest corner along a fixed oblique direction. Each
// triangle not yet used seeds a surface, which then grows from the triangles that touch it (share
// a corner position and the seed's merge keys): each round scores every such candidate and adds
// the best one if it beats the adequate score (110000), or the first that reaches the good score
// (120200) at once. A score is 100000 for a matching lightmap axis (scaled by the cosine
// otherwise), 10000 per corner already in the surface with the same normal, 1000 for coming from
// the seed's own face and up to 200 for not growing the texture range. A candidate is refused
// when it would pass the vertex limit (-mv, or 999 for vertex-lit shaders), the index limit
// (-mi), or make a lightmapped surface wider than sampleSize x (lightmap width - 1) on an axis;
// without -np and q3map_nonplanar a planar surface only takes triangles of its own plane.
#pragma once

#include <vector>

#include "meta_triangles.h"
#include "texture_sizes.h"

namespace q3 {
class ShaderTable;
}

namespace q3::bspstage::meta {

struct MergeLimits {
    int maxLightmappedVerts = 64;  // -mv
    int maxSurfaceVerts = 999;     // vertex-lit surfaces
    int maxIndexes = 6000;         // -mi
    int adequateScore = -1;        // -metaadequatescore (negative: 110000)
    int goodScore = -1;            // -metagoodscore (negative: 120200)
    float npDegrees = 0;           // -np: any angle lifts the same-plane rule
    float maxBBoxDistance = -1;    // -metamaxbboxdistance: a corner must lie this near the bounds
};

struct MergeCounts {
    int surfaces = 0;
    int mergedVerts = 0;  // vertex matches found while scoring, q3map2's "vertexes merged"
};

// Builds the surfaces (kind Meta, not yet classified; lightmapAxis is the seed triangle's) and
// marks every triangle used. Output order is the seeds' order, so it does not depend on threads;
// `table`, when given, orders the shaders as q3map2 does (load order first).
std::vector<DrawSurface> mergeMetaTriangles(MetaTriangles& set, const PlaneSet& planes, const TextureSizes& textures,
                                            const MergeLimits& limits, MergeCounts* counts = nullptr,
                                            const ShaderTable* table = nullptr);

}  // namespace q3::bspstage::meta
