// Biquadratic Bezier patches: a control grid of odd width and height, made of 3x3 sub-patches that
// share their edge rows and columns. Tessellation follows q3map2's lighting mesh: every span of
// three control points is cut into 2^(iterations+1) equal parameter steps, the vertices lie on the
// analytic surface, and each grid quad becomes two triangles with alternating diagonals.
// Everything here is a pure function of its inputs (deterministic, thread-safe).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "vec3.h"

namespace q3::patch {

struct PatchVertex {
    Vec3 xyz;
    Vec3 normal;
    float st[2] = {0, 0};
    float lightmap[2] = {0, 0};
    float color[4] = {255, 255, 255, 255};  // 0..255 per channel, kept in float while interpolating
};

// Control points, row-major: points[row * width + column]; width and height odd and >= 3.
struct ControlGrid {
    int width = 0;
    int height = 0;
    std::vector<PatchVertex> points;

    const PatchVertex& at(int column, int row) const { return points[size_t(row) * width + column]; }
};

// A tessellated patch: a vertex grid (row-major, same orientation as the control grid) and the
// triangle list over it. Triangles follow the Quake 3 convention: for (a, b, c) the front normal is
// (c - a) x (b - a), which agrees with the vertex normals.
struct PatchMesh {
    int width = 0;
    int height = 0;
    std::vector<PatchVertex> verts;
    std::vector<uint32_t> indices;

    const PatchVertex& at(int column, int row) const { return verts[size_t(row) * width + column]; }
};

constexpr int kDefaultSubdivisions = 8;  // q3map2's -subdivisions default
constexpr int kMaxIterations = 3;        // IterationsForCurve never returns more
constexpr int kMaxExpandedAxis = 128;    // an axis keeps fewer vertices than this (q3map2 limit)

// True when the grid has an odd width and height of at least 3 and the right number of points.
bool isValidGrid(const ControlGrid& grid);

// q3map2's estimate of the longest curved span of the control grid (the .srf "longestCurve"): over
// the first row span and first column span of every 3x3 sub-patch that are not straight, the
// length of the 8-step polyline q3map2 measures; 0 for a flat, straight-edged patch. 0 for an
// invalid grid.
float longestCurve(const ControlGrid& grid);
// Subdivision iterations for a curve length (0..kMaxIterations): the first i with
// subdivisions * 16 * 2^i >= length. `subdivisions` below 1 counts as 1, as in q3map2.
int iterationsForCurve(float longestCurve, int subdivisions = kDefaultSubdivisions);

// Level-of-detail groups of one entity's patches: patches sharing a control point (closer than 1
// unit on every axis), directly or through other patches, form a group. Returns a group id per
// patch, numbered 0.. in order of each group's first patch.
std::vector<int> patchLodGroups(std::span<const ControlGrid> grids);
// q3map2 gives every patch its group's longest curve, so that neighbours subdivide alike and their
// shared edges do not pull apart. This is the longestCurve the -bsp stage records per surface.
std::vector<float> groupedLongestCurves(std::span<const ControlGrid> grids);

// Segments per span at a level: 2^(iterations+1) (iterations 0 keeps the three control columns).
int segmentsPerSpan(int iterations);

// Where the surface has no tangent plane (a collapsed edge or a sub-patch squashed to a curve) the
// normal is the limit from just inside the span, else the interpolated one; vertices still without
// a normal after that take the average of the nearest ones along their row and column. Only a
// patch whose control points are all collinear keeps zero normals.
enum class NormalSource {
    Surface,       // normalize(dP/du x dP/dv) of the Bezier surface (u along width, v along height)
    Interpolated,  // the control points' normals blended with the Bezier basis, then normalized
};

struct TessellationOptions {
    int iterations = 0;  // 0..kMaxIterations; reduced per axis to respect kMaxExpandedAxis
    NormalSource normals = NormalSource::Surface;
    // Drop interior rows/columns whose vertices all lie within 0.1 unit of the straight line
    // through their neighbours (q3map2 does this before tracing and lightmap mapping).
    bool removeLinearRowsColumns = false;
};

// Point of the surface at parameters (u, v) in [0,1] over the whole grid (u across width, v down
// height); every attribute is blended with the same biquadratic basis. The normal follows
// NormalSource::Surface, falling back to the interpolated one where the surface is degenerate.
// Throws std::invalid_argument for an invalid grid (as tessellate does).
PatchVertex evaluate(const ControlGrid& grid, float u, float v);
Vec3 evaluatePosition(const ControlGrid& grid, float u, float v);

PatchMesh tessellate(const ControlGrid& grid, const TessellationOptions& options);
// q3map2's -light mesh for a patch: iterations from the longest curve and `subdivisions`, linear
// rows and columns removed, normals interpolated from the control vertices (the BSP's stored
// normals; the surface normal where those are zero). Pass the surface's recorded (LOD-grouped)
// longestCurve when known; the second form measures the grid alone.
PatchMesh tessellateForLighting(const ControlGrid& grid, float longestCurve, int subdivisions = kDefaultSubdivisions);
PatchMesh tessellateForLighting(const ControlGrid& grid);

// Removes interior rows/columns that are straight within `epsilon` (used by tessellate) and
// rebuilds the triangle list.
void removeLinearRowsColumns(PatchMesh& mesh, float epsilon = 0.1f);
// Rebuilds mesh.indices from mesh.width x mesh.height.
void triangulateGrid(PatchMesh& mesh);

Bounds meshBounds(const PatchMesh& mesh);
// Bounds of the control points; they contain the whole surface (convex hull property).
Bounds controlBounds(const ControlGrid& grid);

}  // namespace q3::patch
