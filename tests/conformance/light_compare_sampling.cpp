// Lightmap pages of a lit BSP and the packing-independent mean luminance of one surface.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "file_io.h"
#include "image.h"
#include "light_compare.h"
#include "light_compare_internal.h"

namespace q3::conformance {
namespace fs = std::filesystem;

namespace {

constexpr int kPageSize = 128;

float luminanceOf(float r, float g, float b) { return 0.299f * r + 0.587f * g + 0.114f * b; }

LuminancePage pageFromImage(const Image& image) {
    LuminancePage page;
    page.width = image.width;
    page.height = image.height;
    page.luminance.resize(size_t(image.width) * image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* t = image.texel(x, y);
            page.luminance[size_t(y) * image.width + x] = luminanceOf(t[0], t[1], t[2]);
        }
    return page;
}

// Bilinear between texel centres, clamped at the page's edges (lightmaps do not repeat).
float sampleBilinear(const LuminancePage& page, float s, float t) {
    float x = std::clamp(s * page.width - 0.5f, 0.0f, float(page.width - 1));
    float y = std::clamp(t * page.height - 0.5f, 0.0f, float(page.height - 1));
    int x0 = int(x), y0 = int(y);
    int x1 = std::min(x0 + 1, page.width - 1), y1 = std::min(y0 + 1, page.height - 1);
    float fx = x - float(x0), fy = y - float(y0);
    auto at = [&](int px, int py) { return page.luminance[size_t(py) * page.width + px]; };
    float top = at(x0, y0) * (1 - fx) + at(x1, y0) * fx;
    float bottom = at(x0, y1) * (1 - fx) + at(x1, y1) * fx;
    return top * (1 - fy) + bottom * fy;
}

// Whether a patch's control points lie in one plane (within 0.1 unit): then its control grid is
// the surface itself, and points on it can be tested against solid.
bool flatPatch(const bsp::Bsp& bsp, const bsp::Surface& s) {
    if (s.numVerts < 3 || s.firstVert < 0 || size_t(s.firstVert) + size_t(s.numVerts) > bsp.drawVerts.size())
        return false;
    const Vec3 origin = detail::vertexPosition(bsp, s.firstVert);
    Vec3 normal;
    for (int i = 1; i + 1 < s.numVerts && length(normal) <= 0; ++i)
        for (int j = i + 1; j < s.numVerts && length(normal) <= 0; ++j)
            normal = cross(detail::vertexPosition(bsp, s.firstVert + i) - origin,
                           detail::vertexPosition(bsp, s.firstVert + j) - origin);
    if (length(normal) <= 0) return false;
    normal = normalize(normal);
    for (int i = 0; i < s.numVerts; ++i)
        if (std::fabs(dot(detail::vertexPosition(bsp, s.firstVert + i) - origin, normal)) > 0.1f) return false;
    return true;
}

// Highest lightmapNum any surface uses, or -1.
int highestPage(const bsp::Bsp& bsp) {
    int highest = -1;
    for (const bsp::Surface& s : bsp.surfaces) highest = std::max(highest, s.lightmapNum);
    return highest;
}

// maps/NAME.bsp -> maps/NAME/lm_0000.tga ...: every page up to the highest one used must exist.
std::vector<LuminancePage> externalPages(const fs::path& bspPath, int highest) {
    std::vector<LuminancePage> pages;
    const fs::path folder = bspPath.parent_path() / bspPath.stem();
    for (int i = 0; i <= highest; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "lm_%04d.tga", i);
        const fs::path file = folder / name;
        if (!fs::exists(file))
            throw FileError(bspPath.string() + ": lump 14 is empty and external lightmap " + file.string() +
                            " is missing (surfaces use pages 0.." + std::to_string(highest) + ")");
        pages.push_back(pageFromImage(decodeTga(readFileBytes(file), file.string())));
    }
    return pages;
}

}  // namespace

std::vector<LuminancePage> pagesFromLump(const std::vector<uint8_t>& lump, const std::string& name) {
    if (lump.size() % bsp::kLightmapPageBytes != 0)
        throw bsp::BspError(name + ": lightmaps: " + std::to_string(lump.size()) +
                            " bytes is not a whole number of 128x128 RGB pages");
    std::vector<LuminancePage> pages(lump.size() / bsp::kLightmapPageBytes);
    for (size_t p = 0; p < pages.size(); ++p) {
        LuminancePage& page = pages[p];
        page.width = page.height = kPageSize;
        page.luminance.resize(size_t(kPageSize) * kPageSize);
        const uint8_t* rgb = lump.data() + p * bsp::kLightmapPageBytes;
        for (size_t i = 0; i < page.luminance.size(); ++i)
            page.luminance[i] = luminanceOf(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
    }
    return pages;
}

LitBsp loadLitBsp(const fs::path& path) {
    LitBsp lit;
    lit.name = path.string();
    lit.bsp = bsp::readBsp(path);
    const int highest = highestPage(lit.bsp);
    if (lit.bsp.lightmaps.empty() && highest >= 0) {
        lit.pages = externalPages(path, highest);
        lit.externalPages = true;
    } else {
        lit.pages = pagesFromLump(lit.bsp.lightmaps, lit.name);
    }
    return lit;
}

SurfaceSample sampleSurface(const LitBsp& lit, int surfaceIndex, const detail::SolidTest* solid) {
    SurfaceSample out;
    const bsp::Surface& surface = lit.bsp.surfaces[surfaceIndex];
    if (surface.lightmapNum < 0) return out;
    if (surface.lightmapNum >= int(lit.pages.size()))
        throw bsp::BspError(lit.name + ": surface " + std::to_string(surfaceIndex) + " uses lightmap page " +
                            std::to_string(surface.lightmapNum) + " of " + std::to_string(lit.pages.size()));
    const LuminancePage& page = lit.pages[surface.lightmapNum];

    if (surface.surfaceType == bsp::MST_PATCH && !flatPatch(lit.bsp, surface)) solid = nullptr;
    double weighted = 0, areaSum = 0, unweighted = 0;
    int sampledTriangles = 0;
    int64_t samplesTaken = 0, samplesVisible = 0;
    for (const std::array<int, 3>& tri : detail::surfaceTriangles(lit.bsp, surfaceIndex)) {
        const bsp::DrawVert* v[3] = {&lit.bsp.drawVerts[tri[0]], &lit.bsp.drawVerts[tri[1]], &lit.bsp.drawVerts[tri[2]]};
        float st[3][2];
        bool finite = true;
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 2; ++c) {
                st[k][c] = v[k]->lightmap[c];
                finite = finite && std::isfinite(st[k][c]);
            }
        if (!finite) continue;
        // Longest edge in texels decides how finely the triangle is cut: two samples per texel.
        float longest = 0;
        for (int k = 0; k < 3; ++k) {
            const float* a = st[k];
            const float* b = st[(k + 1) % 3];
            longest = std::max(longest, std::hypot((a[0] - b[0]) * page.width, (a[1] - b[1]) * page.height));
        }
        const int n = std::clamp(int(std::ceil(longest * 2)), 1, 64);
        double sum = 0;
        int count = 0, taken = 0;
        const Vec3 p[3] = {detail::vertexPosition(lit.bsp, tri[0]), detail::vertexPosition(lit.bsp, tri[1]),
                           detail::vertexPosition(lit.bsp, tri[2])};
        const Vec3 vn[3] = {Vec3::fromArray(v[0]->normal), Vec3::fromArray(v[1]->normal), Vec3::fromArray(v[2]->normal)};
        auto sampleAt = [&](float a, float b) {  // barycentric weights of vertexes 1 and 2
            const float c = 1 - a - b;
            ++taken;
            if (solid) {
                Vec3 normal = vn[0] * c + vn[1] * a + vn[2] * b;
                if (length(normal) <= 0) normal = cross(p[2] - p[0], p[1] - p[0]);  // Quake winding order
                if (length(normal) > 0 && solid->inSolid(p[0] * c + p[1] * a + p[2] * b + normalize(normal)))
                    return;
            }
            sum += sampleBilinear(page, c * st[0][0] + a * st[1][0] + b * st[2][0], c * st[0][1] + a * st[1][1] + b * st[2][1]);
            ++count;
        };
        // n*n equal sub-triangles: "upward" ones at (i+1/3, j+1/3)/n, "downward" at (i+2/3, j+2/3)/n.
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                sampleAt((i + 1.0f / 3) / n, (j + 1.0f / 3) / n);
                if (i + j < n - 1) sampleAt((i + 2.0f / 3) / n, (j + 2.0f / 3) / n);
            }
        samplesTaken += taken;
        samplesVisible += count;
        if (count == 0) continue;  // the whole triangle lies against solid
        const double mean = sum / count;
        const double area = detail::triangleArea(p[0], p[1], p[2]) * count / taken;
        weighted += mean * area;
        areaSum += area;
        unweighted += mean;
        ++sampledTriangles;
    }
    if (samplesTaken == 0) return out;
    out.lit = true;
    out.visibleFraction = double(samplesVisible) / double(samplesTaken);
    if (sampledTriangles == 0) {
        out.hidden = true;
        return out;
    }
    out.area = areaSum;
    // Degenerate (zero-area) surfaces still get a mean: the plain mean over their triangles.
    out.mean = areaSum > 0 ? weighted / areaSum : unweighted / sampledTriangles;
    return out;
}

namespace detail {

std::vector<std::array<int, 3>> surfaceTriangles(const bsp::Bsp& bsp, int surfaceIndex) {
    const bsp::Surface& s = bsp.surfaces[surfaceIndex];
    std::vector<std::array<int, 3>> tris;
    if (s.surfaceType == bsp::MST_PATCH) {
        const int w = s.patchWidth, h = s.patchHeight;
        if (w < 2 || h < 2 || int64_t(w) * h > s.numVerts) return tris;
        for (int row = 0; row + 1 < h; ++row)
            for (int col = 0; col + 1 < w; ++col) {
                const int a = s.firstVert + row * w + col;
                const int b = a + 1, c = a + w, d = a + w + 1;
                tris.push_back({a, b, d});
                tris.push_back({a, d, c});
            }
        return tris;
    }
    if (s.surfaceType != bsp::MST_PLANAR && s.surfaceType != bsp::MST_TRIANGLE_SOUP) return tris;
    for (int i = 0; i + 2 < s.numIndexes; i += 3) {
        std::array<int, 3> tri;
        for (int k = 0; k < 3; ++k) tri[k] = s.firstVert + bsp.drawIndexes[s.firstIndex + i + k];
        tris.push_back(tri);
    }
    return tris;
}

SurfaceShape surfaceShape(const bsp::Bsp& bsp, int surfaceIndex) {
    SurfaceShape shape;
    Vec3 weightedCentroid, weightedNormal;
    for (const std::array<int, 3>& tri : surfaceTriangles(bsp, surfaceIndex)) {
        const Vec3 a = vertexPosition(bsp, tri[0]), b = vertexPosition(bsp, tri[1]), c = vertexPosition(bsp, tri[2]);
        const Vec3 n = cross(b - a, c - a);  // length = twice the area
        const float area = 0.5f * length(n);
        weightedCentroid += (a + b + c) * (area / 3);
        weightedNormal += n;
        shape.area += area;
        shape.bounds.add(a);
        shape.bounds.add(b);
        shape.bounds.add(c);
    }
    if (shape.area > 0) shape.centroid = weightedCentroid / float(shape.area);
    else if (!shape.bounds.empty()) shape.centroid = shape.bounds.center();
    shape.normal = normalize(weightedNormal);
    return shape;
}

float boundsDistance(const Bounds& a, const Bounds& b) {
    float sq = 0;
    for (int k = 0; k < 3; ++k) {
        const float gap = std::max({0.0f, a.mins[k] - b.maxs[k], b.mins[k] - a.maxs[k]});
        sq += gap * gap;
    }
    return std::sqrt(sq);
}

float pointBoundsDistance(Vec3 p, const Bounds& b) {
    Bounds point;
    point.add(p);
    return boundsDistance(point, b);
}

}  // namespace detail
}  // namespace q3::conformance
