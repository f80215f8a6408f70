// Compares two lit BSPs made from the same input (same surfaces, same vertexes): one lit by the
// reference q3map2, one by ours. Every figure is independent of how lightmaps are packed into
// pages, so two compilers that place surfaces differently can still be compared.
//
// Lightmaps. For each surface lightmapped by a side (lightmapNum >= 0), its mean luminance
// (0.299 R + 0.587 G + 0.114 B, 0..255) is the area-weighted mean of its lightmap sampled inside
// its triangles: every triangle (draw indexes; a patch's control grid taken as a quad mesh, two
// triangles per quad) is cut into n*n equal sub-triangles, n from its size in lightmap texels
// (two samples per texel along the longest edge, 1..64), and the page is read bilinearly at each
// sub-triangle's centroid through the vertexes' lightmap st. Pages are lump 14 (128x128 RGB) or,
// when lump 14 holds none, maps/NAME/lm_NNNN.tga beside the BSP (-external). The sums run over
// the surfaces the reference lightmapped; one that ours did not lightmap counts as 0 for ours,
// so missing lightmaps pull the ratio down; one-sided counts are reported both ways. Given a second
// reference run, a surface "repeats" when both reference means agree within 2 luminance units or
// 5 %; the ratio and correlation are given again over those surfaces alone.
// Texels that face a wall flush against them (the point 1 unit out along the normal lies in a
// solid leaf or an opaque brush of the reference BSP) are left out of the means, and surfaces made
// only of them out of every figure (CompareOptions::leaveOutHidden): no player sees them, and
// q3map2's values there change between its own runs.
// Worst surfaces are ranked by |ours - ref| / (ref + 8) (relative, near-black damped) times
// min(1, sqrt(area / 4096)) so that slivers smaller than 64x64 units rank lower.
//
// Classes of reference-lightmapped surfaces (ratio of area-weighted summed means, ours /
// reference: the light on the class's area, so a sliver smaller than a luxel weighs as little as
// it shows):
//   planar, patch, soup  surface type MST_PLANAR, MST_PATCH, MST_TRIANGLE_SOUP;
//   near-light   the surface's bounds lie within 128 units of a light entity origin (the .map's
//                entities whose classname starts with "light"; without a .map, the reference
//                BSP's entity lump);
//   shadow       reference mean below 25 % of the median reference mean;
//   area-lit     bounds within 256 units of the bounds of a surface whose shader has
//                q3map_surfacelight > 0 (needs the shader scripts);
//   sky-lit      the map has an emitting sky (a shader with surfaceparm sky and q3map_sun,
//                q3map_sunExt, q3map_skyLight or q3map_surfacelight), and a ray cast straight up
//                from the surface's area centroid (1 unit off the surface along its normal) first
//                meets a sky surface among the opaque drawn surfaces (shader contents neither
//                translucent, fog nor liquid). Needs the shader scripts.
// A class that cannot be measured (no .map and no light entity, no shader scripts) is marked so.
//
// Vertex colours: surfaces the reference left vertex-lit (lightmapNum -3); ratio of summed RGB and
// the correlation of per-vertex luminance.
//
// Legacy light grid (lump 15): counts must match. With a second reference run of the same input
// (another thread count), a point is in the mask when both reference runs agree within 2 on each
// ambient and directed byte, so points where the reference itself is not repeatable do not count,
// and when the reference wrote something there: q3map2 leaves all 8 bytes of a point zero when its
// random search for a free position inside solid gives up, which is chance, not light (ours
// searches the same box in a fixed order; docs/q3map2-differences.md).
// Over the masked points and over all points: ambient and directed totals (ours / reference), the
// Pearson correlation of per-point ambient sums and of directed sums, and the fraction of points
// with reference directed sum >= 30 whose direction (lat/long bytes decoded as ioquake3 does) lies
// within 15 degrees of the reference's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bspfile.h"
#include "vec3.h"

namespace q3::conformance {

// One lightmap page as luminance, row 0 at t = 0.
struct LuminancePage {
    int width = 0;
    int height = 0;
    std::vector<float> luminance;
};

// A lit BSP with its lightmap pages (from lump 14 or the external lm_NNNN.tga files).
struct LitBsp {
    std::string name;  // used in messages
    bsp::Bsp bsp;
    std::vector<LuminancePage> pages;
    bool externalPages = false;
};

// Reads the BSP and its pages. Throws BspError / FileError / ImageError naming the file.
LitBsp loadLitBsp(const std::filesystem::path& path);
// Pages cut from lump 14 (128x128 RGB each); a partial page is an error naming `name`.
std::vector<LuminancePage> pagesFromLump(const std::vector<uint8_t>& lump, const std::string& name);

// What decides class membership; filled by loadClassInputs or directly by tests.
struct ClassInputs {
    bool lightsKnown = false;
    std::vector<Vec3> lightOrigins;
    bool shadersKnown = false;
    std::vector<bool> shaderEmitsArea;  // per BSP shader index: q3map_surfacelight > 0
    std::vector<bool> shaderIsSky;      // per BSP shader index: surface flag sky
    bool skyEmits = false;              // some sky shader gives sun, sky or surface light
};

// Light origins from `mapSource` (or the BSP's entity lump when empty) and, when basePaths is not
// empty, the shaders of the reference BSP looked up in that game's scripts.
ClassInputs loadClassInputs(const bsp::Bsp& reference, const std::filesystem::path& mapSource,
                            const std::vector<std::filesystem::path>& basePaths, const std::string& game);

struct ClassFigures {
    std::string name;
    bool measured = false;
    int surfaces = 0;
    double referenceSum = 0, oursSum = 0;  // sums of mean x area
    double ratio = 0;  // NaN when the class is empty or not measured
};

struct SurfaceFigures {
    int surface = 0;
    std::string shader;
    int surfaceType = 0;
    double area = 0;
    bool referenceLit = false, oursLit = false;
    double referenceMean = 0, oursMean = 0;
    bool referenceRepeats = true;  // false when the second reference run disagrees (see above)
    bool hidden = false;           // entirely against solid (CompareOptions::leaveOutHidden)
    double mismatch = 0;           // ranking score (see above)
};

struct LightmapFigures {
    int referencePages = 0, oursPages = 0;
    int referenceLit = 0, oursLit = 0;     // surfaces with lightmapNum >= 0
    int bothLit = 0, referenceOnly = 0, oursOnly = 0;
    double referenceTotal = 0, oursTotal = 0;
    double ratio = 0;        // oursTotal / referenceTotal, NaN when the reference has none
    double correlation = 0;  // Pearson over reference-lit surfaces; NaN when undefined
    double medianReference = 0;
    int repeatable = -1;  // reference-lit surfaces the second run repeats; -1 without one
    int hiddenSurfaces = 0;  // reference-lit surfaces entirely against solid, left out of every figure
    double repeatableRatio = 0, repeatableCorrelation = 0;
    std::vector<ClassFigures> classes;  // planar, patch, soup, near-light, shadow, area-lit, sky-lit
    std::vector<SurfaceFigures> worst;  // highest mismatch first (including one-sided surfaces)
};

struct VertexFigures {
    int surfaces = 0, vertexes = 0;
    double referenceSum = 0, oursSum = 0;
    double ratio = 0, correlation = 0;  // NaN when undefined
};

struct GridStats {
    int points = 0;
    double ambientRatio = 0, directedRatio = 0;
    double ambientCorrelation = 0, directedCorrelation = 0;
    int directionPoints = 0;        // points with reference directed sum >= 30
    double directionFraction = 0;   // of those, within 15 degrees; NaN when none
};

struct GridFigures {
    int referencePoints = 0, oursPoints = 0;
    bool countsMatch = false;
    bool masked = false;  // a second reference run was given and has the same count
    GridStats all;
    GridStats agreed;     // over the mask; equals `all` in content only when masked is false
};

struct Comparison {
    std::string referenceName, oursName;
    LightmapFigures lightmaps;
    VertexFigures vertexes;
    GridFigures grid;
    std::vector<std::string> notes;  // what could not be measured, and why
};

struct CompareOptions {
    int worstCount = 25;  // surfaces kept in LightmapFigures::worst
    // Leave out texels that face a wall flush against them (see sampleSurface), and surfaces made
    // only of such texels: nobody sees them, and q3map2's values there change from run to run.
    bool leaveOutHidden = true;
};

// Throws BspError naming `ours` when it was not lit from the same input as `reference`
// (different surface or vertex counts, surface types or vertex ranges).
Comparison compareLitBsps(const LitBsp& reference, const LitBsp& ours, const LitBsp* reference2,
                          const ClassInputs& classes, const CompareOptions& options = {});

// Pieces, exposed for tests.
struct SurfaceSample {
    bool lit = false;  // lightmapNum >= 0 and at least one sample inside a triangle
    double mean = 0;
    double area = 0;
    bool hidden = false;           // with `solid`: every sample lies in solid (mean and area 0)
    double visibleFraction = 1;    // with `solid`: the share of samples outside solid
};
namespace detail {
class SolidTest;
}
// With `solid`, samples whose point 1 unit out along the surface normal lies in solid are left
// out: that texel faces a wall flush against it, and no player sees it. Curved patches are sampled
// on their control grid, which is not the surface, so they are always counted whole; flat ones
// (control points within 0.1 unit of a plane) are tested as planar surfaces are.
SurfaceSample sampleSurface(const LitBsp& lit, int surfaceIndex, const detail::SolidTest* solid = nullptr);
GridFigures compareGrids(const std::vector<bsp::GridPoint>& reference, const std::vector<bsp::GridPoint>& ours,
                         const std::vector<bsp::GridPoint>* reference2);
// Whether the point holds anything (q3map2 leaves all 8 bytes zero where it found no free position).
bool gridPointPlaced(const bsp::GridPoint& point);
// Whether both reference runs agree within 2 on every ambient and directed byte of one point.
bool gridPointsAgree(const bsp::GridPoint& a, const bsp::GridPoint& b);
// Unit direction of a grid point's lat/long bytes as ioquake3 decodes them.
Vec3 gridDirection(const bsp::GridPoint& point);
double pearson(const std::vector<double>& a, const std::vector<double>& b);

// Output.
std::string toJson(const Comparison& comparison);
std::string toText(const Comparison& comparison, int worstShown = 15);

}  // namespace q3::conformance
