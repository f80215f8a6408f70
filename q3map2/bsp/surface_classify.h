// Surface classification (q3map2 surface.cpp ClassifySurfaces, BiasSurfaceTextures): whether a
// surface is planar (every vertex within 0.5 of its plane) and on which map plane, its lightmap
// projection axis and its final lightmap sample size; texture coordinates moved near zero.
#pragma once

#include "draw_surface.h"
#include "plane_set.h"

namespace q3::bspstage {

struct ClassifyOptions {
    int maxSurfaceVerts = 999;  // non-face, non-patch surfaces above this become forced meta
    int sampleSize = 16;        // -samplesize
    int minSampleSize = 0;      // -minsamplesize
};

// The axis a planar lightmap is projected along: the dominant axis of the normal (Z wins ties
// within 0.0001, then X), signed like the normal; zero for a zero normal.
Vec3 lightmapAxisForNormal(const Vec3& normal);

// Classifies one surface; planar surfaces without a plane get one in `planes`.
void classifySurface(DrawSurface& ds, PlaneSet& planes, const ClassifyOptions& options);

// Subtracts from every texture coordinate the floor of the middle of the surface's range, per axis,
// unless its shader has q3map_globalTexture.
void biasSurfaceTextures(DrawSurface& ds);

}  // namespace q3::bspstage
