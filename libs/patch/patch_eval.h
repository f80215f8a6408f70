// Internal: evaluation of one 3x3 sub-patch at local parameters, shared by the tessellator.
#pragma once

#include "patch.h"

namespace q3::patch {

// The surface point of sub-patch (spanU, spanV) at local parameters tu, tv in [0,1]. At the
// sub-patch corners (tu and tv each 0 or 1) the position is exactly the corner control point.
PatchVertex evaluateSpan(const ControlGrid& grid, int spanU, double tu, int spanV, double tv, NormalSource normals);

// Throws std::invalid_argument naming the grid's size when isValidGrid fails.
void requireValidGrid(const ControlGrid& grid);

}  // namespace q3::patch
