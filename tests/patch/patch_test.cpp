// Bezier patch tessellation against independent geometry: planes, de Casteljau evaluation,
// control corners, cylinder normals, q3map2's subdivision level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "patch.h"
#include "patch_drawvert.h"

using namespace q3;
using namespace q3::patch;

namespace {

ControlGrid makeGrid(int width, int height, auto&& position) {
    ControlGrid g;
    g.width = width;
    g.height = height;
    for (int row = 0; row < height; ++row)
        for (int column = 0; column < width; ++column) {
            PatchVertex v;
            v.xyz = position(column, row);
            v.st[0] = float(column) / float(width - 1);
            v.st[1] = float(row) / float(height - 1);
            v.lightmap[0] = v.st[0] * 0.5f;
            v.lightmap[1] = v.st[1] * 0.25f;
            g.points.push_back(v);
        }
    return g;
}

// A wavy 5x5 grid with no symmetry, used where a generic curved surface is wanted.
ControlGrid wavyGrid() {
    return makeGrid(5, 5, [](int c, int r) {
        return Vec3(float(c * 32 + ((r * 7 + c * 3) % 5) * 3), float(r * 24 - ((c * 5 + r) % 3) * 4),
                    float(((c * c + 2 * r) % 7) * 9 - 20));
    });
}

// Quadratic Bezier by repeated linear interpolation (de Casteljau), independent of the library's
// Bernstein sums.
Vec3 deCasteljau(Vec3 a, Vec3 b, Vec3 c, double t) {
    auto mix = [](Vec3 p, Vec3 q, double s) {
        return Vec3(float(p.x + (q.x - p.x) * s), float(p.y + (q.y - p.y) * s), float(p.z + (q.z - p.z) * s));
    };
    return mix(mix(a, b, t), mix(b, c, t), t);
}

// Surface point at whole-grid parameters: columns first within each row, then down the column.
Vec3 referencePoint(const ControlGrid& g, double u, double v) {
    const int spansU = (g.width - 1) / 2, spansV = (g.height - 1) / 2;
    int su = std::min(int(u * spansU), spansU - 1), sv = std::min(int(v * spansV), spansV - 1);
    const double tu = u * spansU - su, tv = v * spansV - sv;
    Vec3 rows[3];
    for (int j = 0; j < 3; ++j)
        rows[j] = deCasteljau(g.at(2 * su, 2 * sv + j).xyz, g.at(2 * su + 1, 2 * sv + j).xyz,
                              g.at(2 * su + 2, 2 * sv + j).xyz, tu);
    return deCasteljau(rows[0], rows[1], rows[2], tv);
}

Vec3 triangleNormal(const PatchMesh& m, size_t firstIndex) {
    const Vec3 a = m.verts[m.indices[firstIndex]].xyz;
    const Vec3 b = m.verts[m.indices[firstIndex + 1]].xyz;
    const Vec3 c = m.verts[m.indices[firstIndex + 2]].xyz;
    return cross(c - a, b - a);
}

}  // namespace

TEST(Patch, FlatPatchStaysPlanar) {
    // Irregularly spaced control points, all on the plane 2x - 3y + 6z = 42 (normal length 7).
    const Vec3 planeNormal = normalize(Vec3(2, -3, 6));
    ControlGrid g = makeGrid(7, 5, [](int c, int r) {
        const float x = float(c * 20 + (r % 2) * 7), y = float(r * 30 + c * c);
        return Vec3(x, y, (42 - 2 * x + 3 * y) / 6);
    });
    for (int iterations = 0; iterations <= kMaxIterations; ++iterations) {
        TessellationOptions options;
        options.iterations = iterations;
        PatchMesh mesh = tessellate(g, options);
        ASSERT_EQ(mesh.verts.size(), size_t(mesh.width) * mesh.height);
        for (const PatchVertex& v : mesh.verts) {
            EXPECT_NEAR(2 * v.xyz.x - 3 * v.xyz.y + 6 * v.xyz.z, 42.0f, 2e-3f);
            EXPECT_NEAR(dot(v.normal, planeNormal), 1.0f, 1e-5f);
        }
        for (size_t i = 0; i < mesh.indices.size(); i += 3)
            EXPECT_GT(dot(normalize(triangleNormal(mesh, i)), planeNormal), 0.999f);
    }
}

TEST(Patch, PointsLieOnTheAnalyticSurface) {
    const ControlGrid g = wavyGrid();
    for (int iterations = 0; iterations <= kMaxIterations; ++iterations) {
        TessellationOptions options;
        options.iterations = iterations;
        PatchMesh mesh = tessellate(g, options);
        const int seg = segmentsPerSpan(iterations);
        ASSERT_EQ(mesh.width, 2 * seg + 1);
        ASSERT_EQ(mesh.height, 2 * seg + 1);
        for (int row = 0; row < mesh.height; ++row)
            for (int column = 0; column < mesh.width; ++column) {
                const double u = double(column) / (mesh.width - 1), v = double(row) / (mesh.height - 1);
                const Vec3 expected = referencePoint(g, u, v);
                const Vec3 got = mesh.at(column, row).xyz;
                EXPECT_LT(distance(expected, got), 1e-3f) << "vertex " << column << "," << row << " it " << iterations;
                EXPECT_LT(distance(evaluatePosition(g, float(u), float(v)), got), 1e-3f);
            }
    }
}

TEST(Patch, CornerVerticesEqualControlCorners) {
    const ControlGrid grids[] = {wavyGrid(), makeGrid(3, 9, [](int c, int r) {
                                     return Vec3(float(std::sin(r * 0.7) * 50 + c), float(c * 13), float(r * r));
                                 })};
    for (const ControlGrid& g : grids) {
        for (int iterations = 0; iterations <= kMaxIterations; ++iterations) {
            for (bool removeLinear : {false, true}) {
                TessellationOptions options;
                options.iterations = iterations;
                options.removeLinearRowsColumns = removeLinear;
                PatchMesh mesh = tessellate(g, options);
                EXPECT_EQ(mesh.at(0, 0).xyz, g.at(0, 0).xyz);
                EXPECT_EQ(mesh.at(mesh.width - 1, 0).xyz, g.at(g.width - 1, 0).xyz);
                EXPECT_EQ(mesh.at(0, mesh.height - 1).xyz, g.at(0, g.height - 1).xyz);
                EXPECT_EQ(mesh.at(mesh.width - 1, mesh.height - 1).xyz, g.at(g.width - 1, g.height - 1).xyz);
                EXPECT_EQ(mesh.at(0, 0).st[0], g.at(0, 0).st[0]);
                EXPECT_EQ(mesh.at(mesh.width - 1, mesh.height - 1).st[1], g.at(g.width - 1, g.height - 1).st[1]);
            }
        }
    }
    // Every sub-patch corner is hit exactly too.
    const ControlGrid g = wavyGrid();
    PatchMesh mesh = tessellate(g, {.iterations = 1});
    const int seg = segmentsPerSpan(1);
    for (int r = 0; r < g.height; r += 2)
        for (int c = 0; c < g.width; c += 2) EXPECT_EQ(mesh.at(c / 2 * seg, r / 2 * seg).xyz, g.at(c, r).xyz);
}

TEST(Patch, CylinderNormalsAreRadial) {
    // A quarter cylinder of radius 100 around the z axis, two 45-degree spans, three rows in z.
    // Each span's middle control point sits where the end tangents meet (radius / cos 22.5).
    const double radius = 100, half = kPiD / 8;
    ControlGrid g = makeGrid(5, 3, [&](int c, int r) {
        const double angle = c * half;
        const double rad = (c % 2) ? radius / std::cos(half) : radius;
        return Vec3(float(rad * std::cos(angle)), float(rad * std::sin(angle)), float(r * 64));
    });
    PatchMesh mesh = tessellate(g, {.iterations = 2});
    for (int row = 0; row < mesh.height; ++row)
        for (int column = 0; column < mesh.width; ++column) {
            const PatchVertex& v = mesh.at(column, row);
            const Vec3 radial = normalize(Vec3(v.xyz.x, v.xyz.y, 0));
            EXPECT_NEAR(length(v.normal), 1.0f, 1e-5f);
            EXPECT_NEAR(v.normal.z, 0.0f, 1e-5f);
            // Outward, and within the small angle a quadratic arc differs from a circle.
            EXPECT_GT(dot(v.normal, radial), std::cos(degToRad(1.0f))) << column << "," << row;
            // Span ends and span middles are radial exactly by symmetry.
            if (column % (segmentsPerSpan(2) / 2) == 0) {
                EXPECT_NEAR(dot(v.normal, radial), 1.0f, 1e-5f) << column;
            }
        }
    // Triangles face the same way as the vertex normals.
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        const Vec3 n = normalize(triangleNormal(mesh, i));
        EXPECT_GT(dot(n, mesh.verts[mesh.indices[i]].normal), 0.9f);
    }
}

TEST(Patch, LongestCurveAndIterationsFollowQ3map2) {
    // Flat with straight edges: no curve at all.
    ControlGrid flat = makeGrid(3, 3, [](int c, int r) { return Vec3(float(c * 64), float(r * 64), 0); });
    EXPECT_EQ(longestCurve(flat), 0.0f);
    EXPECT_EQ(iterationsForCurve(longestCurve(flat)), 0);

    // One bent row: |ab| + 7/8 |bc - ab| = 64 + 7/8 * 64 * sqrt(2).
    ControlGrid bent = makeGrid(3, 3, [](int c, int r) {
        if (r == 0) return c == 0 ? Vec3(0, 0, 0) : (c == 1 ? Vec3(64, 0, 0) : Vec3(64, 64, 0));
        return Vec3(float(c * 32), float(c * 32), float(r * 50));
    });
    const double expected = 64 + 7.0 / 8.0 * 64 * std::sqrt(2.0);
    EXPECT_NEAR(longestCurve(bent), expected, 1e-3);
    EXPECT_EQ(iterationsForCurve(longestCurve(bent), 8), 1);

    // q3map2 only measures each sub-patch's first row and first column.
    ControlGrid lastRowBent = makeGrid(3, 3, [](int c, int r) {
        if (r == 2) return c == 1 ? Vec3(64, 500, 128) : Vec3(float(c * 64), 0, 128);
        return Vec3(float(c * 64), 0, float(r * 64));
    });
    EXPECT_EQ(longestCurve(lastRowBent), 0.0f);

    EXPECT_EQ(iterationsForCurve(0, 8), 0);
    EXPECT_EQ(iterationsForCurve(128, 8), 0);
    EXPECT_EQ(iterationsForCurve(128.5f, 8), 1);
    EXPECT_EQ(iterationsForCurve(256.5f, 8), 2);
    EXPECT_EQ(iterationsForCurve(512.5f, 8), 3);
    EXPECT_EQ(iterationsForCurve(1e6f, 8), 3);
    EXPECT_EQ(iterationsForCurve(16, 0), 0);  // subdivisions below 1 count as 1
    EXPECT_EQ(iterationsForCurve(17, 0), 1);
    EXPECT_EQ(iterationsForCurve(17, 2), 0);
    EXPECT_EQ(segmentsPerSpan(0), 2);
    EXPECT_EQ(segmentsPerSpan(3), 16);
}

TEST(Patch, ExpansionLimitLowersTheLevelPerAxis) {
    ControlGrid wide = makeGrid(31, 3, [](int c, int r) { return Vec3(float(c * 16), float((c % 2) * 10), float(r * 16)); });
    PatchMesh mesh = tessellate(wide, {.iterations = 3});
    EXPECT_EQ(mesh.width, 15 * 8 + 1);  // 15 spans at 16 segments would exceed 127 vertices
    EXPECT_EQ(mesh.height, 16 + 1);
    EXPECT_LT(mesh.width, kMaxExpandedAxis);
}

TEST(Patch, LinearRowsAndColumnsAreRemoved) {
    // Flat bilinear patch: everything straight, only the corners remain.
    ControlGrid flat = makeGrid(5, 5, [](int c, int r) { return Vec3(float(c * 10), float(r * 10), 0); });
    PatchMesh mesh = tessellate(flat, {.iterations = 2, .removeLinearRowsColumns = true});
    EXPECT_EQ(mesh.width, 2);
    EXPECT_EQ(mesh.height, 2);
    EXPECT_EQ(mesh.indices.size(), 6u);

    // Curved across, straight along z: the rows collapse, the columns stay.
    ControlGrid arch = makeGrid(3, 5, [](int c, int r) { return Vec3(float(c * 50), c == 1 ? 50.0f : 0.0f, float(r * 30)); });
    PatchMesh archMesh = tessellate(arch, {.iterations = 1, .removeLinearRowsColumns = true});
    EXPECT_EQ(archMesh.width, 5);
    EXPECT_EQ(archMesh.height, 2);
    EXPECT_EQ(archMesh.at(0, 1).xyz, arch.at(0, 4).xyz);
}

TEST(Patch, TrianglesAlternateDiagonalsAndCoverTheGrid) {
    PatchMesh mesh = tessellate(wavyGrid(), {.iterations = 0});
    ASSERT_EQ(mesh.width, 5);
    ASSERT_EQ(mesh.indices.size(), size_t(4 * 4 * 6));
    // Quad (0,0) splits along (0,0)-(1,1); quad (1,0) along (1,1)-(2,0)... i.e. the other diagonal.
    auto has = [&](size_t tri, uint32_t a, uint32_t b) {
        bool ha = false, hb = false;
        for (int k = 0; k < 3; ++k) {
            ha |= mesh.indices[tri * 3 + k] == a;
            hb |= mesh.indices[tri * 3 + k] == b;
        }
        return ha && hb;
    };
    EXPECT_TRUE(has(0, 0, 6) && has(1, 0, 6));
    EXPECT_TRUE(has(2, 6, 2) && has(3, 6, 2));
    std::vector<int> uses(mesh.verts.size(), 0);
    for (uint32_t i : mesh.indices) {
        ASSERT_LT(i, mesh.verts.size());
        ++uses[i];
    }
    for (int u : uses) EXPECT_GT(u, 0);
}

TEST(Patch, AttributesInterpolate) {
    ControlGrid g = makeGrid(3, 3, [](int c, int r) { return Vec3(float(c * 10), float(r * 10), c == 1 ? 8.0f : 0.0f); });
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            PatchVertex& p = g.points[size_t(r) * 3 + c];
            p.color[0] = float(c * 100);  // linear across: stays linear on the surface
            p.color[1] = 50;
            p.color[2] = float(r * 120);
            p.color[3] = 255;
            p.normal = {0, 0, 1};
        }
    PatchMesh mesh = tessellate(g, {.iterations = 1});  // 5x5
    const PatchVertex& centre = mesh.at(2, 2);
    EXPECT_NEAR(centre.color[0], 100, 1e-4);
    EXPECT_NEAR(centre.color[1], 50, 1e-4);
    EXPECT_NEAR(centre.color[2], 120, 1e-4);
    EXPECT_NEAR(mesh.at(1, 3).color[0], 50, 1e-4);
    EXPECT_NEAR(mesh.at(1, 3).color[2], 180, 1e-4);
    EXPECT_NEAR(mesh.at(1, 3).st[0], 0.25, 1e-6);
    EXPECT_NEAR(mesh.at(1, 3).st[1], 0.75, 1e-6);
    EXPECT_NEAR(mesh.at(3, 1).lightmap[0], 0.375, 1e-6);
    EXPECT_NEAR(mesh.at(3, 1).lightmap[1], 0.0625, 1e-6);

    // Interpolated normals follow the control normals, surface normals follow the shape.
    PatchMesh interp = tessellate(g, {.iterations = 1, .normals = NormalSource::Interpolated});
    for (const PatchVertex& v : interp.verts) EXPECT_EQ(v.normal, Vec3(0, 0, 1));
    EXPECT_LT(std::fabs(mesh.at(0, 2).normal.z), 0.99f);  // the bump tilts the edge normal
}

TEST(Patch, DegenerateEdgeStillHasNormals) {
    // A cone: the first row collapses to the apex.
    ControlGrid cone = makeGrid(5, 3, [](int c, int r) {
        if (r == 0) return Vec3(0, 0, 100);
        const double angle = c * kPiD / 4;
        const double rad = ((c % 2) ? 1 / std::cos(kPiD / 8) : 1.0) * r * 40;
        return Vec3(float(rad * std::cos(angle)), float(rad * std::sin(angle)), float(100 - r * 50));
    });
    PatchMesh mesh = tessellate(cone, {.iterations = 1});
    for (const PatchVertex& v : mesh.verts) {
        ASSERT_TRUE(isFinite(v.normal));
        EXPECT_NEAR(length(v.normal), 1.0f, 1e-4f);
    }
    // At the apex the normal leans outwards from the axis like its neighbours below.
    const PatchVertex& apexMid = mesh.at(mesh.width / 2, 0);
    const PatchVertex& below = mesh.at(mesh.width / 2, 1);
    EXPECT_GT(dot(apexMid.normal, below.normal), 0.9f);
}

TEST(Patch, BoundsContainTheMesh) {
    const ControlGrid g = wavyGrid();
    PatchMesh mesh = tessellate(g, {.iterations = 2});
    Bounds mb = meshBounds(mesh);
    Bounds cb = controlBounds(g);
    EXPECT_FALSE(mb.empty());
    for (const PatchVertex& v : mesh.verts) EXPECT_TRUE(mb.contains(v.xyz));
    for (int k = 0; k < 3; ++k) {
        EXPECT_GE(mb.mins[k], cb.mins[k]);
        EXPECT_LE(mb.maxs[k], cb.maxs[k]);
    }
    EXPECT_TRUE(meshBounds(PatchMesh{}).empty());
}

TEST(Patch, InvalidGridsAreRejected) {
    ControlGrid even = makeGrid(4, 3, [](int c, int r) { return Vec3(float(c), float(r), 0); });
    EXPECT_FALSE(isValidGrid(even));
    EXPECT_THROW(tessellate(even, {}), std::invalid_argument);
    ControlGrid shortPoints = makeGrid(3, 3, [](int c, int r) { return Vec3(float(c), float(r), 0); });
    shortPoints.points.pop_back();
    EXPECT_THROW(tessellate(shortPoints, {}), std::invalid_argument);
    EXPECT_THROW(evaluate(shortPoints, 0.5f, 0.5f), std::invalid_argument);
    EXPECT_EQ(longestCurve(shortPoints), 0.0f);
}

TEST(Patch, DrawVertConversionRoundTrips) {
    bsp::DrawVert dv{};
    dv.xyz[0] = 1;
    dv.xyz[1] = 2;
    dv.xyz[2] = 3;
    dv.st[0] = 0.5f;
    dv.lightmap[1] = 0.25f;
    dv.normal[2] = 1;
    dv.color[0] = 10;
    dv.color[3] = 255;
    const bsp::DrawVert back = toDrawVert(fromDrawVert(dv));
    EXPECT_EQ(std::memcmp(&dv, &back, sizeof dv), 0);

    PatchVertex v;
    v.color[0] = 300;
    v.color[1] = -4;
    v.color[2] = 127.6f;
    const bsp::DrawVert clamped = toDrawVert(v);
    EXPECT_EQ(clamped.color[0], 255);
    EXPECT_EQ(clamped.color[1], 0);
    EXPECT_EQ(clamped.color[2], 128);

    std::vector<bsp::DrawVert> verts(9, dv);
    ControlGrid g = gridFromDrawVerts(verts, 3, 3);
    EXPECT_EQ(g.points.size(), 9u);
    EXPECT_THROW(gridFromDrawVerts(verts, 3, 5), std::invalid_argument);
    EXPECT_THROW(gridFromDrawVerts(std::span<const bsp::DrawVert>(verts).first(6), 2, 3), std::invalid_argument);
}

TEST(Patch, LightingMeshUsesTheCurveLevel) {
    // A half pipe 512 units across: long curve, so the lighting mesh is subdivided.
    ControlGrid pipe = makeGrid(3, 3, [](int c, int r) {
        return Vec3(float(c * 256), 0, c == 1 ? 400.0f : 0.0f) + Vec3(0, float(r * 64), 0);
    });
    const int level = iterationsForCurve(longestCurve(pipe), kDefaultSubdivisions);
    EXPECT_GT(level, 0);
    PatchMesh mesh = tessellateForLighting(pipe);
    EXPECT_EQ(mesh.width, segmentsPerSpan(level) + 1);
    EXPECT_EQ(mesh.height, 2);  // straight along y
    // A larger recorded (grouped) curve raises the level; a flat group keeps the control rows.
    EXPECT_EQ(tessellateForLighting(pipe, 600.0f).width, segmentsPerSpan(3) + 1);
    EXPECT_EQ(tessellateForLighting(pipe, 0.0f).width, segmentsPerSpan(0) + 1);
    PatchMesh again = tessellateForLighting(pipe);
    ASSERT_EQ(again.verts.size(), mesh.verts.size());
    EXPECT_EQ(std::memcmp(again.verts.data(), mesh.verts.data(), mesh.verts.size() * sizeof(PatchVertex)), 0);
}

TEST(Patch, CollapsedSpanBorrowsNeighbourNormals) {
    // Rows 2..4 coincide (a sub-patch squashed to a curve, as editors leave behind): the vertices
    // inside it have no tangent plane and take the normals of the rows next to them.
    ControlGrid g = makeGrid(3, 5, [](int c, int r) {
        const int rr = std::min(r, 2);
        return Vec3(float(c * 64), float(rr * 64), c == 1 ? 20.0f : 0.0f);
    });
    PatchMesh mesh = tessellate(g, {.iterations = 1});
    for (const PatchVertex& v : mesh.verts) {
        ASSERT_TRUE(isFinite(v.normal));
        EXPECT_NEAR(length(v.normal), 1.0f, 1e-4f);
        EXPECT_GT(v.normal.z, 0.5f);  // the surface faces +z: columns run +x, rows +y
    }
}

TEST(Patch, LodGroupsShareTheLongestCurve) {
    // A: a long curved strip. B: flat, sharing A's right edge (within 1 unit). C: flat, touching B
    // only through a point 0.9 units away on each axis. D: flat, alone (1.0 away is not shared).
    ControlGrid a = makeGrid(3, 3, [](int c, int r) { return Vec3(float(c * 200), float(r * 64), c == 1 ? 300.0f : 0.0f); });
    ControlGrid b = makeGrid(3, 3, [](int c, int r) { return Vec3(400.0f + float(c * 32), float(r * 64), 0.5f); });
    ControlGrid c = makeGrid(3, 3, [](int cc, int r) { return Vec3(464.9f + float(cc * 32), 128.9f + float(r * 32), 0.9f); });
    ControlGrid d = makeGrid(3, 3, [](int cc, int r) { return Vec3(-1.0f - float(cc * 32), float(r * 32), 0.0f); });
    const std::vector<ControlGrid> grids = {a, b, c, d};
    const std::vector<int> groups = patchLodGroups(grids);
    EXPECT_EQ(groups, (std::vector<int>{0, 0, 0, 1}));
    const std::vector<float> curves = groupedLongestCurves(grids);
    ASSERT_GT(longestCurve(a), 0.0f);
    EXPECT_EQ(longestCurve(b), 0.0f);
    EXPECT_EQ(curves[0], longestCurve(a));
    EXPECT_EQ(curves[1], longestCurve(a));
    EXPECT_EQ(curves[2], longestCurve(a));
    EXPECT_EQ(curves[3], 0.0f);
    EXPECT_TRUE(patchLodGroups(std::span<const ControlGrid>()).empty());
}
