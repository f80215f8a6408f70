#include "lightmap_layout.h"
#include "lightmap_layout_mapping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace q3::light {

int resolveSampleSize(bool srfLoaded, int srfSampleSize, int shaderSampleSize, int defaultSampleSize, int sampleScale) {
    int size = srfLoaded ? srfSampleSize : (shaderSampleSize > 0 ? shaderSampleSize : defaultSampleSize);
    if (size <= 0) size = defaultSampleSize > 0 ? defaultSampleSize : kDefaultSampleSize;
    if (sampleScale > 0) size *= sampleScale;
    return std::max(1, size);
}

bool isLightmappedSurface(const bsp::Surface& surface, bool shaderVertexLit) {
    // q3map2 SetupSurfaceLightmaps: the type and the shader decide; whatever lightmapNum an earlier
    // run left in the file does not (a BSP fresh from -bsp has -3 everywhere).
    const bool lightmappableType = surface.surfaceType == bsp::MST_PLANAR || surface.surfaceType == bsp::MST_PATCH;
    return lightmappableType && !shaderVertexLit;
}

SurfaceGeometry surfaceGeometry(const bsp::Bsp& bsp, int surfaceIndex, std::span<const Vec3> normals) {
    SurfaceGeometry g;
    const bsp::Surface& s = bsp.surfaces.at(size_t(surfaceIndex));
    g.surfaceIndex = surfaceIndex;
    g.surfaceType = s.surfaceType;
    g.positions.reserve(size_t(std::max(0, s.numVerts)));
    for (int i = 0; i < s.numVerts; ++i) {
        const size_t index = size_t(s.firstVert) + i;
        const bsp::DrawVert& v = bsp.drawVerts.at(index);
        g.positions.push_back(Vec3::fromArray(v.xyz));
        g.normals.push_back(index < normals.size() ? normals[index] : Vec3::fromArray(v.normal));
    }
    for (int i = 0; i + 2 < s.numIndexes; i += 3)
        for (int k = 0; k < 3; ++k) {
            const int32_t index = bsp.drawIndexes.at(size_t(s.firstIndex) + i + k);
            g.triangles.push_back(index >= 0 && index < s.numVerts ? uint32_t(index) : 0u);
        }
    g.planeNormal = Vec3::fromArray(s.lightmapVecs[2]);
    g.patchWidth = s.patchWidth;
    g.patchHeight = s.patchHeight;
    return g;
}

patch::ControlGrid patchControlGrid(const bsp::Bsp& bsp, const bsp::Surface& s, Vec3 offset,
                                    std::span<const Vec3> normals) {
    patch::ControlGrid grid;
    grid.width = s.patchWidth;
    grid.height = s.patchHeight;
    for (int v = 0; v < s.numVerts; ++v) {
        const size_t vi = size_t(s.firstVert + v);
        const bsp::DrawVert& dv = bsp.drawVerts.at(vi);
        patch::PatchVertex pv;
        pv.xyz = Vec3::fromArray(dv.xyz) + offset;
        pv.normal = vi < normals.size() ? normals[vi] : Vec3::fromArray(dv.normal);
        pv.st[0] = dv.st[0];
        pv.st[1] = dv.st[1];
        pv.lightmap[0] = dv.lightmap[0];
        pv.lightmap[1] = dv.lightmap[1];
        grid.points.push_back(pv);
    }
    return grid;
}

CurvedMesh curvedMesh(const bsp::Bsp& bsp, const bsp::Surface& s, std::span<const Vec3> normals, float longestCurve) {
    patch::ControlGrid grid = patchControlGrid(bsp, s, Vec3{}, normals);
    for (size_t v = 0; v < grid.points.size(); ++v) {
        grid.points[v].st[0] = float(int(v) % std::max(1, s.patchWidth));
        grid.points[v].st[1] = float(int(v) / std::max(1, s.patchWidth));
    }
    CurvedMesh mesh;
    if (!patch::isValidGrid(grid)) return mesh;
    const patch::PatchMesh tess =
        longestCurve > 0.0f ? patch::tessellateForLighting(grid, longestCurve) : patch::tessellateForLighting(grid);
    mesh.width = tess.width;
    mesh.height = tess.height;
    for (const patch::PatchVertex& v : tess.verts) {
        mesh.positions.push_back(v.xyz);
        mesh.normals.push_back(v.normal);
        mesh.controlU.push_back(v.st[0]);
        mesh.controlV.push_back(v.st[1]);
    }
    return mesh;
}

void applyLightmapOrigin(bsp::Surface& surface, const RawLightmap& lightmap) {
    if (lightmap.axisNum < 0) return;  // curved patches keep what -bsp wrote
    lightmap.origin.toArray(surface.lightmapOrigin);
}

namespace {

using St = std::array<float, 2>;
constexpr int kMaxGrownSampleSize = 1 << 20;  // beyond the world size: give up growing

Vec3 vertexNormal(const SurfaceGeometry& g, size_t i) {
    return i < g.normals.size() ? g.normals[i] : Vec3{};
}

// q3map2 AddSurfaceToRawLightmap for surfaces projected along an axis.
// Triangles of one surface projected into the lightmap by `project`.
template <typename Project>
void addSurfaceTriangles(RawLightmap& lm, const SurfaceGeometry& g, const Project& project) {
    if (g.surfaceType == bsp::MST_PATCH && g.mesh.width >= 2 && g.mesh.height >= 2 &&
        g.mesh.positions.size() == size_t(g.mesh.width) * g.mesh.height) {
        // A flat patch: its tessellation gives the exact outline (curved edges, degenerate rows).
        const CurvedMesh& m = g.mesh;
        auto corner = [&](int x, int y, LightmapTriangle& t, int k) {
            const size_t i = size_t(y) * m.width + x;
            t.st[size_t(k)] = project(m.positions[i]);
            t.position[size_t(k)] = m.positions[i];
            t.normal[size_t(k)] = i < m.normals.size() ? m.normals[i] : g.planeNormal;
        };
        for (int y = 0; y + 1 < m.height; ++y)
            for (int x = 0; x + 1 < m.width; ++x) {
                LightmapTriangle a, b;
                corner(x, y, a, 0), corner(x, y + 1, a, 1), corner(x + 1, y + 1, a, 2);
                corner(x, y, b, 0), corner(x + 1, y + 1, b, 1), corner(x + 1, y, b, 2);
                lm.triangles.push_back(a);
                lm.triangles.push_back(b);
            }
        return;
    }
    for (size_t i = 0; i + 2 < g.triangles.size(); i += 3) {
        LightmapTriangle t;
        bool valid = true;
        for (int k = 0; k < 3 && valid; ++k) {
            const uint32_t v = g.triangles[i + size_t(k)];
            valid = v < g.positions.size();
            if (!valid) break;
            t.st[size_t(k)] = project(g.positions[v]);
            t.position[size_t(k)] = g.positions[v];
            t.normal[size_t(k)] = vertexNormal(g, v);
        }
        if (valid) lm.triangles.push_back(t);
    }
}

// What q3map2 maps of a projected surface: a flat patch's tessellation quad by quad, else its
// triangles.
template <typename Project>
MappingSurface projectedMappingSurface(const SurfaceGeometry& g, const Project& project) {
    MappingSurface out;
    const CurvedMesh& m = g.mesh;
    if (g.surfaceType == bsp::MST_PATCH && m.width >= 2 && m.height >= 2 && m.positions.size() == size_t(m.width) * m.height) {
        for (size_t i = 0; i < m.positions.size(); ++i)
            out.verts.push_back({project(m.positions[i]), m.positions[i], i < m.normals.size() ? m.normals[i] : g.planeNormal});
        out.quadWidth = m.width;
        out.quadHeight = m.height;
        return out;
    }
    for (size_t i = 0; i < g.positions.size(); ++i) out.verts.push_back({project(g.positions[i]), g.positions[i], vertexNormal(g, i)});
    out.triangles = g.triangles;
    return out;
}

// q3map2 AddSurfaceToRawLightmap for surfaces projected along an axis. The first surface of the
// group defines the plane; all share the bounds, size and projection.
std::optional<RawLightmap> layoutProjected(std::span<const SurfaceGeometry> group, Vec3 axis,
                                           const SurfaceLightmapParams& params, const LayoutOptions& options,
                                           int pageW, int pageH, Log* log) {
    const SurfaceGeometry& g = group[0];
    RawLightmap lm;
    lm.surfaceIndex = g.surfaceIndex;
    lm.superSample = std::clamp(options.superSample, 1, kMaxSuperSample);
    lm.requestedSampleSize = std::max(1, params.sampleSize);
    lm.sampleOffset = params.sampleOffset;
    lm.planar = dot(g.planeNormal, g.planeNormal) > 0.0f;
    lm.planeNormal = g.planeNormal;

    Bounds bounds;
    for (const SurfaceGeometry& member : group)
        for (const Vec3& p : member.positions) bounds.add(p);
    if (bounds.empty() || g.positions.empty()) return std::nullopt;

    // Snap to the luxel grid; grow the sample size while any side would exceed the page.
    int sampleSize = lm.requestedSampleSize;
    Vec3 mins, maxs;
    std::array<int, 3> size{};
    for (;;) {
        bool fits = true;
        const float ss = float(sampleSize);
        for (int i = 0; i < 3; ++i) {
            mins[i] = ss * std::floor(bounds.mins[i] / ss);
            maxs[i] = ss * std::ceil(bounds.maxs[i] / ss);
            size[i] = int((maxs[i] - mins[i]) / ss + 1.0f);
            if (size[i] > pageW || size[i] > pageH || (options.rawSizeLimit > 0 && size[i] > options.rawSizeLimit))
                fits = false;
        }
        if (fits) break;
        if (++sampleSize > kMaxGrownSampleSize) {
            // Tiny pages (a surface straddling a grid line never fits one luxel) would loop forever.
            if (log) log->warning("surface " + std::to_string(g.surfaceIndex) + " cannot fit a " + std::to_string(pageW) +
                                  "x" + std::to_string(pageH) + " lightmap at any sample size");
            return std::nullopt;
        }
    }
    lm.sampleSize = sampleSize;
    if (sampleSize != lm.requestedSampleSize && options.rawSizeLimit == 0 && log) {
        char text[320];
        std::snprintf(text, sizeof(text),
                      "surface %d at (%6.0f %6.0f %6.0f) (%6.0f %6.0f %6.0f) too large for desired "
                      "samplesize/lightmapsize/lightmapscale combination, increased samplesize from %d to %d",
                      g.surfaceIndex, bounds.mins.x, bounds.mins.y, bounds.mins.z, bounds.maxs.x, bounds.maxs.y,
                      bounds.maxs.z, lm.requestedSampleSize, sampleSize);
        log->warning(text);
    }

    // Planar surfaces start at their real minimum; others at the snapped one (as q3map2).
    const Vec3 start = lm.planar ? bounds.mins : mins;
    const Vec3 fa{std::fabs(axis.x), std::fabs(axis.y), std::fabs(axis.z)};
    int sAxis, tAxis;
    if (fa.z >= fa.x && fa.z >= fa.y) {  // z wins ties: floors and ceilings keep x/y mapping
        lm.axisNum = 2, sAxis = 0, tAxis = 1;
    } else if (fa.x >= fa.y && fa.x >= fa.z) {
        lm.axisNum = 0, sAxis = 1, tAxis = 2;
    } else {
        lm.axisNum = 1, sAxis = 0, tAxis = 2;
    }
    if (fa[lm.axisNum] == 0.0f) {
        if (log) log->warning("surface " + std::to_string(g.surfaceIndex) + ": lightmap projection chose a zero axis");
        return std::nullopt;
    }
    lm.width = size[size_t(sAxis)];
    lm.height = size[size_t(tAxis)];

    const float inv = 1.0f / float(sampleSize);
    for (const SurfaceGeometry& member : group) {
        lm.surfaces.push_back(member.surfaceIndex);
        auto& coords = lm.surfaceCoords.emplace_back();
        coords.reserve(member.positions.size());
        for (const Vec3& p : member.positions) {
            const Vec3 d = p - start;
            coords.push_back({d[sAxis] * inv + 0.5f, d[tAxis] * inv + 0.5f});
        }
    }
    lm.vertexCoords = lm.surfaceCoords[0];

    // Origin and per-luxel steps projected along the axis onto the surface plane. A forced axis
    // lying in the plane cannot project onto it: luxels then come from the triangles.
    Vec3 planeN = lm.planar ? g.planeNormal : axis;
    if (std::fabs(planeN[lm.axisNum]) < 1e-6f) {
        lm.planar = false;
        planeN = {};
        planeN[lm.axisNum] = 1.0f;
    }
    const float planeD = dot(g.positions[0], planeN);
    lm.planeDist = lm.planar ? planeD : 0.0f;
    lm.origin = start;
    lm.origin[lm.axisNum] -= (dot(lm.origin, planeN) - planeD) / planeN[lm.axisNum];
    for (int i = 0; i < 2; ++i) {
        Vec3 v;
        v[i == 0 ? sAxis : tAxis] = float(sampleSize);
        v[lm.axisNum] -= dot(v, planeN) / planeN[lm.axisNum];
        lm.vecs[size_t(i)] = v;
    }
    lm.vecs[2] = g.planeNormal;

    const float S = float(lm.superSample);
    auto project = [&](Vec3 p) -> St {
        const Vec3 d = p - start;
        return {(d[sAxis] * inv + 0.5f) * S, (d[tAxis] * inv + 0.5f) * S};
    };
    std::vector<MappingSurface> mapping;
    for (const SurfaceGeometry& member : group) {
        addSurfaceTriangles(lm, member, project);
        mapping.push_back(projectedMappingSurface(member, project));
    }
    mapSurfacesOntoLuxels(lm, mapping);
    return lm;
}

// The control grid itself as a mesh, for patches given without a tessellation.
CurvedMesh controlGridMesh(const SurfaceGeometry& g) {
    CurvedMesh m;
    m.width = g.patchWidth;
    m.height = g.patchHeight;
    m.positions = g.positions;
    m.normals = g.normals;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            m.controlU.push_back(float(x));
            m.controlV.push_back(float(y));
        }
    return m;
}

// q3map2 AddPatchToRawLightmap: a curved patch gets a lightmap sized from the longest row/column
// lengths of its mesh, with coordinates linear in the control-point indices.
std::optional<RawLightmap> layoutCurvedPatch(const SurfaceGeometry& g, const SurfaceLightmapParams& params,
                                             const LayoutOptions& options, int pageW, int pageH, Log* log) {
    if (g.patchWidth < 2 || g.patchHeight < 2 || size_t(g.patchWidth) * g.patchHeight != g.positions.size()) {
        if (log) log->warning("surface " + std::to_string(g.surfaceIndex) + ": patch control grid does not match its vertices");
        return std::nullopt;
    }
    const CurvedMesh mesh = g.mesh.width >= 2 && g.mesh.height >= 2 ? g.mesh : controlGridMesh(g);
    const size_t count = size_t(mesh.width) * mesh.height;
    if (mesh.positions.size() != count || mesh.controlU.size() != count || mesh.controlV.size() != count) {
        if (log) log->warning("surface " + std::to_string(g.surfaceIndex) + ": patch mesh is inconsistent");
        return std::nullopt;
    }

    RawLightmap lm;
    lm.surfaceIndex = g.surfaceIndex;
    lm.superSample = std::clamp(options.superSample, 1, kMaxSuperSample);
    lm.requestedSampleSize = lm.sampleSize = std::max(1, params.sampleSize);
    lm.sampleOffset = params.sampleOffset;
    lm.axisNum = -1;

    std::vector<float> widthTable(size_t(mesh.width), 0.0f), heightTable(size_t(mesh.height), 0.0f);
    auto at = [&](int x, int y) { return mesh.positions[size_t(y) * mesh.width + x]; };
    for (int y = 0; y < mesh.height; ++y)
        for (int x = 0; x < mesh.width; ++x) {
            if (x + 1 < mesh.width) widthTable[size_t(x)] = std::max(widthTable[size_t(x)], distance(at(x, y), at(x + 1, y)));
            if (y + 1 < mesh.height) heightTable[size_t(y)] = std::max(heightTable[size_t(y)], distance(at(x, y), at(x, y + 1)));
        }
    float lengthS = 0, lengthT = 0;
    for (int x = 0; x + 1 < mesh.width; ++x) lengthS += widthTable[size_t(x)];
    for (int y = 0; y + 1 < mesh.height; ++y) lengthT += heightTable[size_t(y)];
    const float ss = float(lm.sampleSize);
    lm.width = std::min(std::max(int(std::ceil(lengthS / ss)) + 1, g.patchWidth), pageW);
    lm.height = std::min(std::max(int(std::ceil(lengthT / ss)) + 1, g.patchHeight), pageH);
    const float sBasis = float(lm.width - 1) / float(g.patchWidth - 1);
    const float tBasis = float(lm.height - 1) / float(g.patchHeight - 1);

    for (int y = 0; y < g.patchHeight; ++y)
        for (int x = 0; x < g.patchWidth; ++x) lm.vertexCoords.push_back({sBasis * float(x) + 0.5f, tBasis * float(y) + 0.5f});
    lm.surfaces = {g.surfaceIndex};
    lm.surfaceCoords = {lm.vertexCoords};

    const float S = float(lm.superSample);
    auto corner = [&](int x, int y, LightmapTriangle& t, int k) {
        const size_t i = size_t(y) * mesh.width + x;
        t.st[size_t(k)] = {(sBasis * mesh.controlU[i] + 0.5f) * S, (tBasis * mesh.controlV[i] + 0.5f) * S};
        t.position[size_t(k)] = mesh.positions[i];
        t.normal[size_t(k)] = i < mesh.normals.size() ? mesh.normals[i] : Vec3{};
    };
    MappingSurface mapping;
    mapping.quadWidth = mesh.width;
    mapping.quadHeight = mesh.height;
    for (size_t i = 0; i < count; ++i)
        mapping.verts.push_back({{(sBasis * mesh.controlU[i] + 0.5f) * S, (tBasis * mesh.controlV[i] + 0.5f) * S},
                                 mesh.positions[i], i < mesh.normals.size() ? mesh.normals[i] : Vec3{}});
    for (int y = 0; y + 1 < mesh.height; ++y)
        for (int x = 0; x + 1 < mesh.width; ++x) {
            // Alternate the quad diagonal as q3map2 does ((x + y) & 1).
            const int quad[5][2] = {{x, y}, {x, y + 1}, {x + 1, y + 1}, {x + 1, y}, {x, y}};
            const int r = (x + y) & 1;
            LightmapTriangle a, b;
            corner(quad[r][0], quad[r][1], a, 0);
            corner(quad[r + 1][0], quad[r + 1][1], a, 1);
            corner(quad[r + 2][0], quad[r + 2][1], a, 2);
            corner(quad[r][0], quad[r][1], b, 0);
            corner(quad[r + 2][0], quad[r + 2][1], b, 1);
            corner(quad[r + 3][0], quad[r + 3][1], b, 2);
            lm.triangles.push_back(a);
            lm.triangles.push_back(b);
        }
    mapSurfacesOntoLuxels(lm, std::span(&mapping, 1));
    return lm;
}

}  // namespace

Vec3 lightmapProjectionAxis(const SurfaceGeometry& g, const SurfaceLightmapParams& params) {
    Vec3 axis = params.axis;
    if (dot(axis, axis) == 0.0f) axis = g.planeNormal;
    if (dot(axis, axis) == 0.0f) {
        if (g.surfaceType == bsp::MST_PATCH) return {};  // curved: mapped by its control grid
        // Non-planar soups project along their average normal.
        for (const Vec3& n : g.normals) axis += n;
        if (dot(axis, axis) == 0.0f) axis = {0, 0, 1};
    }
    return axis;
}

std::optional<RawLightmap> layoutSurfaceLightmap(const SurfaceGeometry& g, const SurfaceLightmapParams& params,
                                                 const LayoutOptions& options, Log* log) {
    return layoutSurfaceGroup(std::span(&g, 1), params, options, log);
}

std::optional<RawLightmap> layoutSurfaceGroup(std::span<const SurfaceGeometry> group, const SurfaceLightmapParams& params,
                                              const LayoutOptions& options, Log* log) {
    if (group.empty() || group[0].positions.empty()) return std::nullopt;
    const int pageW = params.pageWidth > 0 ? params.pageWidth : options.pageSize;
    const int pageH = params.pageHeight > 0 ? params.pageHeight : options.pageSize;

    const Vec3 axis = lightmapProjectionAxis(group[0], params);
    if (dot(axis, axis) == 0.0f) {
        if (group.size() > 1) {
            if (log) log->warning("surface " + std::to_string(group[0].surfaceIndex) + ": a curved patch cannot share a lightmap");
            return std::nullopt;
        }
        return layoutCurvedPatch(group[0], params, options, pageW, pageH, log);
    }
    std::vector<SurfaceGeometry> prepared(group.begin(), group.end());
    for (SurfaceGeometry& g : prepared) {
        if (g.surfaceType != bsp::MST_PATCH || !g.triangles.empty() || g.mesh.width >= 2) continue;
        // A flat patch without a tessellation: triangulate its control grid.
        for (int y = 0; y + 1 < g.patchHeight; ++y)
            for (int x = 0; x + 1 < g.patchWidth; ++x) {
                const uint32_t i = uint32_t(y * g.patchWidth + x), w = uint32_t(g.patchWidth);
                g.triangles.insert(g.triangles.end(), {i, i + w, i + w + 1, i, i + w + 1, i + 1});
            }
    }
    return layoutProjected(prepared, axis, params, options, pageW, pageH, log);
}


}  // namespace q3::light
