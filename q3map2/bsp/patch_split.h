// Cutting a patch's control grid by a plane (q3map2 fog.cpp SplitMeshByPlane), used to cut patches
// by the top and bottom of fog volumes: the grid is cut between two columns that every row crosses
// at the same place (transposing first when the first row is not crossed), each piece padded to an
// odd width with a copy of the cut column.
#pragma once

#include <optional>
#include <vector>

#include "bspfile.h"
#include "dvec3.h"

namespace q3::bspstage {

struct PatchGrid {
    int width = 0;
    int height = 0;
    std::vector<bsp::DrawVert> verts;  // row-major

    bsp::DrawVert& at(int x, int y) { return verts[size_t(y) * size_t(width) + size_t(x)]; }
    const bsp::DrawVert& at(int x, int y) const { return verts[size_t(y) * size_t(width) + size_t(x)]; }
};

// Rows become columns.
PatchGrid transposeGrid(const PatchGrid& in);
// Each row reversed.
void invertGrid(PatchGrid& grid);

struct GridSplit {
    std::optional<PatchGrid> front, back;
};

// Splits by `plane` (points within 0.1 count as on it). A grid not crossed, or crossed in a way a
// single column cut cannot follow, comes back whole on one side.
GridSplit splitGridByPlane(PatchGrid grid, const DPlane& plane);

// A vertex `amount` of the way from a to b (q3map2 LerpDrawVertAmount).
bsp::DrawVert lerpDrawVert(const bsp::DrawVert& a, const bsp::DrawVert& b, float amount);

}  // namespace q3::bspstage
