// T-junction fixing (q3map2 tjunction.cpp FixTJunctions): where a vertex of one face lies on the
// edge of another, that edge gets the vertex too, so that the engine's rasteriser leaves no cracks.
// Every face edge (a face's closing edge first) and every straight border of a patch is registered
// on an edge line: edges whose ends lie within 0.25 of the same line (along each of two planes
// through it) share it and add their end points to it, axial edges first, then the others from
// shortest to longest. Each face then takes, along each of its edges, the points of the edge's line
// strictly between its ends (0.1 inward), with interpolated texture coordinates; a face not already
// starting between two unsplit edges starts at its second vertex, and vertices closer than 0.1 are
// welded. Faces left with fewer than three vertices are dropped.
#pragma once

#include <vector>

#include "draw_surface.h"

namespace q3::bspstage {

struct TJunctionCounts {
    int axialLines = 0;
    int nonAxialLines = 0;
    int degenerateEdges = 0;
    int addedVerts = 0;
    int totalVerts = 0;
    int natural = 0;
    int rotated = 0;
    int cantOrder = 0;
    int broken = 0;
};

// Fixes the faces among `surfaces` (one entity's); broken faces are left empty (kind Bad).
TJunctionCounts fixTJunctions(std::vector<DrawSurface>& surfaces);

}  // namespace q3::bspstage
