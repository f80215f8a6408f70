// Raw lightmaps: for each lightmapped BSP surface, the luxel grid q3map2 would allocate (projection
// axis, sample size, size, super-sampling) and the world position and normal of every luxel.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "bspfile.h"
#include "log.h"
#include "patch.h"
#include "vec3.h"

namespace q3::light {

constexpr int kDefaultSampleSize = 16;  // DEFAULT_LIGHTMAP_SAMPLE_SIZE
constexpr int kMaxSuperSample = 8;

// Stage-wide options.
struct LayoutOptions {
    int superSample = 1;   // -super N (clamped to 1..8; the caller warns)
    int sampleScale = 0;   // -samplescale N (0 = off)
    int pageSize = 128;    // -lightmapsize: the largest raw lightmap side
    int rawSizeLimit = 0;  // -rawlightmapsizelimit (0 = none)
};

// Per-surface inputs resolved by the caller from the .srf, the shader and the command line.
struct SurfaceLightmapParams {
    int sampleSize = kDefaultSampleSize;  // resolveSampleSize()
    Vec3 axis{0, 0, 0};                   // forced projection axis (.srf lightmapAxis, q3map_lightmapAxis)
    float sampleOffset = 1.0f;            // q3map_lightmapSampleOffset: push-off of luxel sample points
    int pageWidth = 0, pageHeight = 0;    // q3map_lightmapSize (0 = LayoutOptions::pageSize)
};

// Sample size of a surface: the .srf value when the file was loaded (it already includes the shader's
// q3map_lightmapSampleSize and entity keys), else the shader's value when set, else -samplesize; then
// multiplied by -samplescale when that is > 0. Never below 1.
int resolveSampleSize(bool srfLoaded, int srfSampleSize, int shaderSampleSize, int defaultSampleSize, int sampleScale);

// True for surfaces that get a lightmap, decided as q3map2 does from the surface type and the shader
// only: planar and patch surfaces whose shader is not vertex lit (surfaceparm nolightmap /
// pointlight). Triangle soups and foliage are vertex lit; the lightmapNum in the file is ignored.
bool isLightmappedSurface(const bsp::Surface& surface, bool shaderVertexLit);

// A tessellated patch: a width x height grid of points on the curved surface. controlU/V is the
// position of each point in control-point index space (0..patchWidth-1, 0..patchHeight-1), which is
// what the lightmap coordinates of a curved patch are linear in.
struct CurvedMesh {
    int width = 0, height = 0;
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<float> controlU, controlV;
};

// The control grid of a patch surface in world space (`offset` = its brush model's origin), with
// texture st, BSP lightmap st, and the normals of `normals` (per BSP draw vertex) when given.
patch::ControlGrid patchControlGrid(const bsp::Bsp& bsp, const bsp::Surface& s, Vec3 offset,
                                    std::span<const Vec3> normals = {});
// The lighting tessellation of a patch for the layout: each point's position in control-point index
// space is carried through the tessellation in the st channel (Bezier blending of evenly spaced
// indices is linear, so the result is the exact control-space coordinate). Model space.
// `longestCurve` > 0: the surface's recorded (LOD-grouped) longest curve from the .srf, which sets
// the subdivision as q3map2's mapping does; 0 measures the grid alone.
CurvedMesh curvedMesh(const bsp::Bsp& bsp, const bsp::Surface& s, std::span<const Vec3> normals = {},
                      float longestCurve = 0.0f);

// What the layout needs of one BSP surface.
struct SurfaceGeometry {
    int surfaceIndex = -1;
    int surfaceType = bsp::MST_BAD;
    std::vector<Vec3> positions;          // the surface's draw verts
    std::vector<Vec3> normals;
    std::vector<uint32_t> triangles;      // index triples into positions (planar and soups)
    Vec3 planeNormal{0, 0, 0};            // lightmapVecs[2]; zero when not planar
    int patchWidth = 0, patchHeight = 0;  // control grid of patches
    CurvedMesh mesh;                      // tessellation of a patch (empty: the control grid is used)
};

// Copies one surface's vertices, triangles and plane out of the BSP (the mesh stays empty).
// `normals`, when not empty, holds the normal of every draw vertex of the BSP to use instead of the
// stored ones (phong shading: LightContext::shadedNormals).
SurfaceGeometry surfaceGeometry(const bsp::Bsp& bsp, int surfaceIndex, std::span<const Vec3> normals = {});

// One super-sampled luxel.
struct Luxel {
    // Where light is sampled: on the surface, pushed off by the sample offset. Planar lightmaps push
    // along their projection axis (towards the side the plane faces), curved ones along the plane
    // of the triangle under the luxel, as q3map2 MapSingleLuxel does.
    Vec3 origin;
    Vec3 normal;          // interpolated, unit length
    bool mapped = false;  // false: no triangle covers it (to be filled from neighbours)
    // The surface point that mapped the luxel first (q3map2's last resort when the sample point and
    // its nudges are all in solid is this point pushed off along surfaceNormal), and the plane it
    // was mapped with (its normal spans the nudges of curved lightmaps).
    Vec3 surfacePoint;
    Vec3 surfaceNormal;
    Vec3 faceNormal;
};

// A triangle in super-luxel space (luxel (x,y) spans [x, x+1) x [y, y+1)) with world attributes.
struct LightmapTriangle {
    std::array<std::array<float, 2>, 3> st;
    std::array<Vec3, 3> position;
    std::array<Vec3, 3> normal;
};

struct RawLightmap {
    int surfaceIndex = -1;                   // the first (plane-defining) surface
    std::vector<int> surfaces;               // every surface drawn with this lightmap, first included
    // Lightmap coordinates of each surface's draw vertices (same order as `surfaces`).
    std::vector<std::vector<std::array<float, 2>>> surfaceCoords;
    int requestedSampleSize = kDefaultSampleSize;
    int sampleSize = kDefaultSampleSize;  // after growing to fit the page
    int axisNum = -1;                     // 0, 1, 2: projection axis; -1: curved patch
    bool planar = false;
    Vec3 planeNormal{0, 0, 0};
    float planeDist = 0.0f;
    int width = 0, height = 0;            // BSP luxels
    int superSample = 1;
    // BSP lightmapOrigin / lightmapVecs: world position of luxel (0,0) and the world step of one
    // luxel along s and t (in the surface plane); vecs[2] is the plane normal. Zero for curved patches.
    Vec3 origin{0, 0, 0};
    std::array<Vec3, 3> vecs{};
    // Lightmap coordinate of each draw vertex of the first surface in BSP luxel units (0..width,
    // 0..height; a luxel centre is at x + 0.5), as q3map2 stores them before packing.
    std::vector<std::array<float, 2>> vertexCoords;
    std::vector<LightmapTriangle> triangles;  // the surfaces in super-luxel space
    std::vector<Luxel> luxels;                // superWidth() * superHeight(), row-major
    float sampleOffset = 1.0f;

    int superWidth() const { return width * superSample; }
    int superHeight() const { return height * superSample; }
    const Luxel& luxel(int x, int y) const { return luxels[size_t(y) * superWidth() + x]; }
};

// The projection axis of a surface: the forced axis, else the plane normal, else (soups) the sum
// of the vertex normals; zero for a curved patch (mapped through its control grid instead).
Vec3 lightmapProjectionAxis(const SurfaceGeometry& geometry, const SurfaceLightmapParams& params);

// Lays out one surface: projection axis (z-biased dominant axis of the plane normal or the forced
// axis), bounds snapped to the sample size, size = extent/sampleSize + 1 with the sample size grown
// while a side exceeds the page (q3map2's "too large for desired samplesize" warning to `log`),
// curved patches sized from their row/column lengths, then every super luxel mapped. Returns nullopt
// (with a warning) for degenerate surfaces.
std::optional<RawLightmap> layoutSurfaceLightmap(const SurfaceGeometry& geometry, const SurfaceLightmapParams& params,
                                                 const LayoutOptions& options, Log* log = nullptr);

// Lays out several surfaces sharing one raw lightmap (see lightmap_layout_merge.h): bounds, size and
// projection cover them all, the first surface defines the plane. Curved patches cannot share.
std::optional<RawLightmap> layoutSurfaceGroup(std::span<const SurfaceGeometry> group, const SurfaceLightmapParams& params,
                                              const LayoutOptions& options, Log* log = nullptr);

// Writes the lightmap origin of a laid-out surface into the BSP surface as q3map2 does
// (lightmapOrigin only; lightmapVecs keep what -bsp wrote, patches use them as LOD bounds).
void applyLightmapOrigin(bsp::Surface& surface, const RawLightmap& lightmap);

}  // namespace q3::light
