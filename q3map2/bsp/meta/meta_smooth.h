// Normal smoothing of meta triangles (q3map2 surface_meta.cpp SmoothMetaTriangles): at every
// position where several triangle corners meet, corners whose normals differ by less than their
// shade angle (the shader's q3map_shadeAngle, else the entity's _shadeangle, else -np; the smaller
// of the two corners') take the normalised sum of their distinct normals (normals within 0.01 of
// one already counted are counted once). Corners without any shade angle are left alone.
#pragma once

#include "meta_triangles.h"

namespace q3::bspstage::meta {

// Returns the number of smoothed corner sets ("smoothed vertexes"). `npDegrees` is -np.
int smoothMetaTriangles(MetaTriangles& set, float npDegrees);

}  // namespace q3::bspstage::meta
