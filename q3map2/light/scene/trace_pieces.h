// The shadow casters as q3map2's tracer sees them (light_trace.cpp SetupTraceNodes): every caster
// triangle is cut by the planes of the BSP tree it is filtered down, the windings that reach a
// leaf are cut again by the axial planes of its subdivision, and each piece is fanned into
// triangles. Its ray test (TraceTriangle) then accepts hits up to 1 % of a piece outside its edges
// (barycentric epsilon 0.01) and never hits a piece whose edge cross product is below 0.25 (its
// coplanar epsilon on the determinant, which is at most that length). A ray that passes just
// beside a large face is therefore blocked by it; how far beside depends on the size of the piece
// the tree cut, so the pieces are what the scene must hold.
#pragma once

#include <vector>

#include "bspfile.h"
#include "sky_ray_solid.h"
#include "trace_scene.h"

namespace q3::light {

// Barycentric slack of q3map2's ray-triangle test (BARY_EPSILON).
constexpr float kTraceBaryEpsilon = 0.01f;
// q3map2 skips a triangle whose determinant (ray direction against its edge cross product) is
// below this (COPLANAR_EPSILON): a piece whose cross product is shorter is never hit.
constexpr float kTraceCoplanarEpsilon = 0.25f;

struct CasterPieces {
    // The input surfaces with each caster's triangles replaced by its pieces.
    std::vector<SceneSurface> surfaces;
    // Per input surface, its opaque pieces in leaves outside every cluster that the tracer split:
    // only sun rays can meet them (TraceScene's sunOnly). Empty when there are none at all.
    std::vector<SceneSurface> forSunOnly;
};

// `surfaces` with the triangles of every caster replaced by its trace pieces, each grown by the
// barycentric slack (filtering surfaces keep their exact pieces: q3map2 reads their texture only
// inside the triangle; only theirs keep texture coordinates). Surfaces that cast nothing are
// returned unchanged. Opaque pieces in leaves outside every cluster, which only rays through such
// a leaf could meet and which the solid tests stop there, are left out, or kept apart for sun rays
// where the tracer split the leaf (unless options.sunRays is false). Without BSP nodes the
// triangles are only grown. `contents`, when given, receives what each BSP leaf holds. Surfaces
// are filtered and leaves subdivided on `threads` threads (0: one per core); the result does not
// depend on their number.
CasterPieces traceCasterPieces(const std::vector<SceneSurface>& surfaces, const bsp::Bsp& bsp,
                               const TraceSceneOptions& options, TraceLeafContents* contents = nullptr,
                               int threads = 0);

}  // namespace q3::light
