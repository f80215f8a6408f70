// Surface geometry shared by the comparator's sampling and its surface classes.
#pragma once

#include <array>
#include <vector>

#include "bspfile.h"
#include "vec3.h"

namespace q3::conformance::detail {

// Triangles of one surface as absolute draw-vertex indexes: draw indexes for planar and soup
// surfaces, the control grid as a quad mesh (two triangles per quad) for patches, none otherwise.
std::vector<std::array<int, 3>> surfaceTriangles(const bsp::Bsp& bsp, int surfaceIndex);

inline Vec3 vertexPosition(const bsp::Bsp& bsp, int vertex) { return Vec3::fromArray(bsp.drawVerts[vertex].xyz); }

inline double triangleArea(Vec3 a, Vec3 b, Vec3 c) { return 0.5 * double(length(cross(b - a, c - a))); }

// Area-weighted centroid, area-weighted geometric normal (unit; zero when degenerate) and bounds.
struct SurfaceShape {
    Vec3 centroid;
    Vec3 normal;
    Bounds bounds;
    double area = 0;
};
SurfaceShape surfaceShape(const bsp::Bsp& bsp, int surfaceIndex);

// Distance between two boxes (0 when they overlap) and from a point to a box.
float boundsDistance(const Bounds& a, const Bounds& b);
float pointBoundsDistance(Vec3 p, const Bounds& b);

// Per surface: a ray cast straight up from its area centroid (1 unit off along its normal) first
// meets an opaque drawn surface whose shader is a sky (see light_compare.h, sky-lit).
std::vector<bool> skyLitSurfaces(const bsp::Bsp& bsp, const std::vector<bool>& shaderIsSky);

// Whether a point lies in a solid leaf of the BSP tree or inside an opaque (CONTENTS_SOLID) brush
// of its leaf. A BSP without nodes has no solid.
class SolidTest {
public:
    explicit SolidTest(const bsp::Bsp& bsp);
    bool inSolid(Vec3 point) const;

private:
    const bsp::Bsp& bsp_;
};

}  // namespace q3::conformance::detail
