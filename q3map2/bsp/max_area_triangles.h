// -maxarea triangulation of face surfaces (q3map2 surface_meta.cpp MaxAreaFaceSurface): the
// face's largest triangle (scored by area minus a perimeter penalty, so slivers lose) is cut out
// and the three polygons left beside it are triangulated the same way. A polygon whose best
// triangle is a sliver (twice the area under 1) is retried with random triangles, seven times at
// most; when that fails too the face is stripped as without -maxarea.
#pragma once

#include "draw_surface.h"
#include "libc_random.h"
#include "surface_triangles.h"

namespace q3::bspstage {

// Fills ds.indexes of a face surface; `random` supplies the retries in surface order.
void triangulateFaceByMaxArea(DrawSurface& ds, LibcRandom& random, TriangulationCounts* counts = nullptr);

}  // namespace q3::bspstage
