// autosprite2 quads (q3map2 surface.cpp FixAutosprite2Surface): the engines' autosprite2 deform
// reads the quad's long axis from its vertex order, so a quad is rewritten in the one order every
// engine handles: the two shortest edges as (0, 1) and (2, 3), both running along the quad's
// minor axis in opposite directions, and the triangles (3, 0, 2) and (2, 0, 1).
#pragma once

#include <string>

#include "draw_surface.h"

namespace q3::bspstage {

// Reorders a four-vertex, six-index surface. Returns an empty string, or the reason it was left
// alone (q3map2 warns with it): not a simple rectangle, a degenerate first triangle, or two
// shortest edges sharing a vertex (a square).
std::string fixAutosprite2(DrawSurface& ds);

}  // namespace q3::bspstage
