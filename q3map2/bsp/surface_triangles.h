// Triangles of face surfaces and their index order (q3map2 surface_meta.cpp StripFaceSurface,
// FanFaceSurface; surface.cpp OptimizeTriangleSurface): a face becomes a strip that walks its
// winding from both ends at once, starting at its lowest vertex (later rotations tried in turn)
// and preferring to spend T-junction vertices early; a strip with a sliver triangle (twice the
// area at most 1, or a smallest angle with sin^2 at most 1e-5) is rejected, and if every strip
// is, the face becomes a fan around a new centre vertex. Indexes are then reordered for a
// 16-entry vertex cache.
#pragma once

#include "draw_surface.h"

namespace q3::bspstage {

struct TriangulationCounts {
    int strips = 0;
    int fans = 0;
    int maxArea = 0;  // -maxarea triangulations that succeeded
};

// Fills ds.indexes of a face surface (adding the centre vertex when it has to fan). Throws
// CompileError when the face has more than 1024 indexes (q3map2's MAX_INDEXES).
void triangulateFace(DrawSurface& ds, TriangulationCounts* counts = nullptr);

// Twice the area of a triangle, and the squared sine of its smallest angle.
double triangleArea2x(const Vec3& a, const Vec3& b, const Vec3& c);
double triangleMinAngleSquaredSin(const Vec3& a, const Vec3& b, const Vec3& c);

// Reorders the triangles of a surface with more than 16 indexes so that each one reuses as many of
// the last 16 vertices as possible, each rotated so its smallest index comes first.
void optimizeForVertexCache(std::vector<int>& indexes);

}  // namespace q3::bspstage
