// Phong shading (phong.h): the smoothing of coincident vertex normals on small hand-built BSPs,
// with the exact normals each rule gives, and the pipeline step on a LightContext.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "bsp_scene.h"
#include "light_context.h"
#include "lightmap_layout.h"
#include "phong.h"
#include "phong_reference.h"
#include "shader_info.h"

namespace q3::light {
namespace {

using q3::test::addQuad;

constexpr float kHalfRoot2 = 0.70710678f;

void expectNormal(Vec3 got, Vec3 want, const char* what) {
    EXPECT_NEAR(got.x, want.x, 1e-6f) << what;
    EXPECT_NEAR(got.y, want.y, 1e-6f) << what;
    EXPECT_NEAR(got.z, want.z, 1e-6f) << what;
}

bsp::Bsp emptyBsp(int shaderCount) {
    bsp::Bsp b;
    b.version = bsp::kVersionQ3;
    b.headerLumps = 18;
    for (int i = 0; i < shaderCount; ++i) {
        bsp::Shader sh{};
        std::snprintf(sh.name, sizeof(sh.name), "textures/phong/s%d", i);
        b.shaders.push_back(sh);
    }
    return b;
}

void addModel(bsp::Bsp& b, int firstSurface, int numSurfaces) {
    bsp::Model m{};
    m.firstSurface = firstSurface;
    m.numSurfaces = numSurfaces;
    b.models.push_back(m);
}

// A floor (normal +z, shader `floorShader`) and a wall (normal +x, shader `wallShader`) meeting
// along the line x = 0, z = 0 from y = 0 to y = 64. Verts: floor 0..3, wall 4..7; the shared
// corners are floor 0 (0,0,0) and 1 (0,64,0), wall 4 (0,0,0) and 7 (0,64,0).
void addCorner(bsp::Bsp& b, Vec3 at, int floorShader, int wallShader) {
    addQuad(b, at, {0, 64, 0}, {64, 0, 0}, floorShader);
    addQuad(b, at, {0, 0, 64}, {0, 64, 0}, wallShader);
}

struct Plain {
    std::vector<Vec3> positions, normals;
};

Plain plainVertices(const bsp::Bsp& b) {
    Plain p;
    for (const bsp::DrawVert& v : b.drawVerts) {
        p.positions.push_back(Vec3::fromArray(v.xyz));
        p.normals.push_back(Vec3::fromArray(v.normal));
    }
    return p;
}

// The whole rule chain without a context: per-surface shader angles, entity angles per model,
// default angle.
SmoothedNormals smooth(const bsp::Bsp& b, std::vector<float> shaderAnglesPerShader, std::vector<float> modelAngles,
                       float defaultAngle) {
    std::vector<float> surfaceShader(b.surfaces.size(), 0.0f);
    for (size_t s = 0; s < b.surfaces.size(); ++s)
        surfaceShader[s] = shaderAnglesPerShader.at(static_cast<size_t>(b.surfaces[s].shaderNum));
    const std::vector<float> surfaceAngles = surfaceShadeAngles(b, surfaceShader, modelAngles, defaultAngle);
    const Plain p = plainVertices(b);
    return smoothVertexNormals(p.positions, p.normals, vertexShadeAngles(b, surfaceAngles));
}

TEST(Phong, RightAngleSmoothsBelowTheBreakingAngleOnly) {
    bsp::Bsp b = emptyBsp(1);
    addCorner(b, {0, 0, 0}, 0, 0);
    addModel(b, 0, 2);

    const SmoothedNormals wide = smooth(b, {100}, {0}, 0);
    EXPECT_EQ(wide.smoothedVertexes, 4u);
    for (int v : {0, 1, 4, 7}) expectNormal(wide.normals[v], {kHalfRoot2, 0, kHalfRoot2}, "shared corner");
    for (int v : {2, 3}) expectNormal(wide.normals[v], {0, 0, 1}, "floor far edge");
    for (int v : {5, 6}) expectNormal(wide.normals[v], {1, 0, 0}, "wall top edge");

    const SmoothedNormals narrow = smooth(b, {80}, {0}, 0);
    EXPECT_EQ(narrow.smoothedVertexes, 0u);
    for (int v : {0, 1, 2, 3}) expectNormal(narrow.normals[v], {0, 0, 1}, "floor");
    for (int v : {4, 5, 6, 7}) expectNormal(narrow.normals[v], {1, 0, 0}, "wall");
}

TEST(Phong, DefaultAngleAppliesToSurfacesWithoutTheirOwn) {
    bsp::Bsp b = emptyBsp(1);
    addCorner(b, {0, 0, 0}, 0, 0);
    addModel(b, 0, 2);
    EXPECT_EQ(smooth(b, {0}, {0}, 0).smoothedVertexes, 0u);  // bare -shade: nothing asks
    const SmoothedNormals withDefault = smooth(b, {0}, {0}, 91);
    EXPECT_EQ(withDefault.smoothedVertexes, 4u);
    expectNormal(withDefault.normals[4], {kHalfRoot2, 0, kHalfRoot2}, "wall corner");
}

// An octagonal prism: 8 walls around the z axis, 45 degrees apart, normals facing out.
bsp::Bsp makePrism(float radius) {
    bsp::Bsp b = emptyBsp(1);
    const int sides = 8;
    for (int k = 0; k < sides; ++k) {
        const float a0 = degToRad(45.0f * k), a1 = degToRad(45.0f * (k + 1));
        const Vec3 p0{radius * std::cos(a0), radius * std::sin(a0), 0};
        const Vec3 p1{radius * std::cos(a1), radius * std::sin(a1), 0};
        addQuad(b, p0, {0, 0, 64}, p1 - p0, 0);  // normal cross(p1 - p0, +z): outward
    }
    addModel(b, 0, sides);
    return b;
}

TEST(Phong, PrismEdgesTakeTheRadialDirection) {
    const bsp::Bsp b = makePrism(100);
    const SmoothedNormals wide = smooth(b, {60}, {0}, 0);
    EXPECT_EQ(wide.smoothedVertexes, 32u);  // every vertex: 8 edges x top and bottom x 2 walls
    for (int k = 0; k < 8; ++k) {
        // Wall k's verts: 0 = (a_k, z 0), 1 = (a_k, z 64), 2 = (a_k+1, z 64), 3 = (a_k+1, z 0).
        const float a0 = degToRad(45.0f * k), a1 = degToRad(45.0f * (k + 1));
        const size_t first = static_cast<size_t>(k) * 4;
        expectNormal(wide.normals[first + 0], {std::cos(a0), std::sin(a0), 0}, "edge k bottom");
        expectNormal(wide.normals[first + 1], {std::cos(a0), std::sin(a0), 0}, "edge k top");
        expectNormal(wide.normals[first + 2], {std::cos(a1), std::sin(a1), 0}, "edge k+1 top");
        expectNormal(wide.normals[first + 3], {std::cos(a1), std::sin(a1), 0}, "edge k+1 bottom");
    }
    const SmoothedNormals narrow = smooth(b, {44}, {0}, 0);
    EXPECT_EQ(narrow.smoothedVertexes, 0u);
    const Plain p = plainVertices(b);
    for (size_t v = 0; v < p.normals.size(); ++v) EXPECT_EQ(narrow.normals[v], p.normals[v]);
}

TEST(Phong, TwoShadersUseTheSmallerAngle) {
    // Floor and wall 90 degrees apart: 100 and 80 -> 80 breaks; 100 and 0 -> the wall never smooths.
    bsp::Bsp b = emptyBsp(3);
    addCorner(b, {0, 0, 0}, 0, 1);
    addModel(b, 0, 2);
    EXPECT_EQ(smooth(b, {100, 80, 0}, {0}, 0).smoothedVertexes, 0u);
    EXPECT_EQ(smooth(b, {100, 0, 0}, {0}, 0).smoothedVertexes, 0u);
    EXPECT_EQ(smooth(b, {100, 95, 0}, {0}, 0).smoothedVertexes, 4u);

    // A crease of 20 degrees: shader 0 at 30, shader 2 at 100 -> 30 > 20, smoothed.
    bsp::Bsp crease = emptyBsp(3);
    const float s = std::sin(degToRad(20.0f)), c = std::cos(degToRad(20.0f));
    addQuad(crease, {0, 0, 0}, {0, 64, 0}, {64, 0, 0}, 0);               // flat, +z
    addQuad(crease, {0, 0, 0}, {-64 * c, 0, 64 * s}, {0, 64, 0}, 2);     // tilted 20 degrees
    addModel(crease, 0, 2);
    const SmoothedNormals r = smooth(crease, {30, 0, 100}, {0}, 0);
    EXPECT_EQ(r.smoothedVertexes, 4u);
    const Vec3 tilted = Vec3::fromArray(crease.drawVerts[4].normal);
    const Vec3 expected = normalize(Vec3{0, 0, 1} + tilted);
    expectNormal(r.normals[0], expected, "crease corner");
    expectNormal(r.normals[4], expected, "crease corner, second surface");
    EXPECT_EQ(smooth(crease, {15, 0, 100}, {0}, 0).smoothedVertexes, 0u);
}

TEST(Phong, TriangleSoupsAreLeftAlone) {
    bsp::Bsp b = emptyBsp(1);
    addCorner(b, {0, 0, 0}, 0, 0);
    b.surfaces[1].surfaceType = bsp::MST_TRIANGLE_SOUP;
    addModel(b, 0, 2);
    const SmoothedNormals r = smooth(b, {100}, {0}, 0);
    EXPECT_EQ(r.smoothedVertexes, 0u);
    expectNormal(r.normals[0], {0, 0, 1}, "floor");
    expectNormal(r.normals[4], {1, 0, 0}, "soup");
}

TEST(Phong, EqualNormalsVoteOnce) {
    // Three vertices at one point: two floor normals and one wall normal average to the diagonal,
    // not to (2, 0, 1).
    const std::vector<Vec3> positions{{5, 5, 5}, {5, 5, 5}, {5.0005f, 5, 5}};
    const std::vector<Vec3> normals{{0, 0, 1}, {0, 0.005f, 0.99999f}, {1, 0, 0}};
    const SmoothedNormals r = smoothVertexNormals(positions, normals, std::vector<float>{100, 100, 100});
    EXPECT_EQ(r.smoothedVertexes, 3u);
    for (const Vec3& n : r.normals) expectNormal(n, {kHalfRoot2, 0, kHalfRoot2}, "diagonal");
}

TEST(Phong, GroupsFormInVertexOrderAroundTheFirstVertex) {
    // Angles measured from vertex 0: 50 (joins at 60) and 100 (does not). Vertex 2 is then alone,
    // although it is only 50 degrees from vertex 1.
    const Vec3 n0{0, 0, 1};
    const Vec3 n1{std::sin(degToRad(50)), 0, std::cos(degToRad(50))};
    const Vec3 n2{std::sin(degToRad(100)), 0, std::cos(degToRad(100))};
    const std::vector<Vec3> positions(3, Vec3{1, 2, 3});
    const SmoothedNormals r = smoothVertexNormals(positions, std::vector<Vec3>{n0, n1, n2}, std::vector<float>(3, 60));
    EXPECT_EQ(r.smoothedVertexes, 2u);
    expectNormal(r.normals[0], normalize(n0 + n1), "first");
    expectNormal(r.normals[1], normalize(n0 + n1), "second");
    EXPECT_EQ(r.normals[2], n2);
}

TEST(Phong, PositionsFartherThanTheEpsilonStayApart) {
    const std::vector<Vec3> positions{{0, 0, 0}, {0.002f, 0, 0}};
    const std::vector<Vec3> normals{{0, 0, 1}, {1, 0, 0}};
    EXPECT_EQ(smoothVertexNormals(positions, normals, std::vector<float>{100, 100}).smoothedVertexes, 0u);
    const std::vector<Vec3> close{{0.9996f, 0, 0}, {1.0004f, 0, 0}};  // across a hash cell boundary
    EXPECT_EQ(smoothVertexNormals(close, normals, std::vector<float>{100, 100}).smoothedVertexes, 2u);
}

// q3map2's loop, quadratic, as the reference the hashed version must equal exactly.
// Every vertex against every later one (quadratic).
std::vector<Vec3> bruteForce(const std::vector<Vec3>& p, const std::vector<Vec3>& n, const std::vector<float>& deg) {
    std::vector<float> radians(p.size());
    for (size_t i = 0; i < p.size(); ++i) radians[i] = deg[i] > 0 ? degToRad(deg[i]) : 0.0f;
    std::vector<Vec3> out = n;
    std::vector<bool> grouped(p.size(), false);
    std::vector<size_t> later;
    for (size_t i = 0; i < p.size(); ++i) {
        if (grouped[i] || radians[i] <= 0) continue;
        later.clear();
        for (size_t j = i; j < p.size(); ++j) later.push_back(j);
        referenceSmoothGroup(i, later, p, n, radians, grouped, out);
    }
    return out;
}

TEST(Phong, HashedGroupingEqualsTheQuadraticLoop) {
    // 3000 vertices on few positions straddling hash cell boundaries, with varied normals and angles.
    std::vector<Vec3> p, n;
    std::vector<float> deg;
    uint32_t state = 12345;
    auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return state >> 8;
    };
    for (int i = 0; i < 3000; ++i) {
        const float jitter[3] = {-0.0004f, 0.0f, 0.0004f};
        p.push_back({float(next() % 4) + jitter[next() % 3], float(next() % 3) + jitter[next() % 3], float(next() % 2)});
        const float yaw = degToRad(float(next() % 360)), pitch = degToRad(float(next() % 180) - 90.0f);
        n.push_back({std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)});
        deg.push_back(next() % 5 == 0 ? 0.0f : float(next() % 120));
    }
    const SmoothedNormals hashed = smoothVertexNormals(p, n, deg);
    const std::vector<Vec3> reference = bruteForce(p, n, deg);
    EXPECT_GT(hashed.smoothedVertexes, 100u);
    size_t changed = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        EXPECT_EQ(hashed.normals[i], reference[i]) << "vertex " << i;
        changed += hashed.normals[i] == n[i] ? 0 : 1;
    }
    EXPECT_GT(changed, 100u);
}

TEST(Phong, HundredThousandVerticesStayLinear) {
    // A 160 x 160 grid of quads (102,400 verts, each inner corner shared by 4 quads).
    bsp::Bsp b = emptyBsp(1);
    for (int y = 0; y < 160; ++y)
        for (int x = 0; x < 160; ++x) addQuad(b, {x * 16.0f, y * 16.0f, 0}, {0, 16, 0}, {16, 0, 0}, 0);
    addModel(b, 0, static_cast<int>(b.surfaces.size()));
    const SmoothedNormals r = smooth(b, {45}, {0}, 0);
    EXPECT_EQ(r.smoothedVertexes, b.drawVerts.size() - 4);  // all but the 4 outer corners
    for (const Vec3& n : r.normals) expectNormal(n, {0, 0, 1}, "flat");
}

TEST(Phong, LightmapLayoutInterpolatesTheGivenNormals) {
    bsp::Bsp b = emptyBsp(1);
    addCorner(b, {0, 0, 0}, 0, 0);
    addModel(b, 0, 2);
    const SmoothedNormals r = smooth(b, {100}, {0}, 0);

    const SurfaceGeometry stored = surfaceGeometry(b, 0);
    const SurfaceGeometry shaded = surfaceGeometry(b, 0, r.normals);
    for (int v = 0; v < 4; ++v) {
        EXPECT_EQ(stored.normals[v], Vec3(0, 0, 1));
        EXPECT_EQ(shaded.normals[v], r.normals[v]);
    }
    // Luxel normals lean towards the wall near the shared edge (x = 0) and stay up at x = 64.
    const std::optional<RawLightmap> lm = layoutSurfaceLightmap(shaded, SurfaceLightmapParams{}, LayoutOptions{});
    ASSERT_TRUE(lm);
    float nearEdge = -1, farEdge = 2;
    for (const Luxel& lx : lm->luxels) {
        if (!lx.mapped) continue;
        EXPECT_NEAR(length(lx.normal), 1.0f, 1e-5f);
        if (lx.origin.x < 4) nearEdge = std::max(nearEdge, lx.normal.x);
        if (lx.origin.x > 60) farEdge = std::min(farEdge, lx.normal.x);
    }
    EXPECT_GT(nearEdge, 0.6f);  // close to the corner's diagonal (0.707)
    EXPECT_LT(farEdge, 0.1f);
    const std::optional<RawLightmap> flat = layoutSurfaceLightmap(stored, SurfaceLightmapParams{}, LayoutOptions{});
    ASSERT_TRUE(flat);
    for (const Luxel& lx : flat->luxels) {
        if (lx.mapped) {
            EXPECT_EQ(lx.normal, Vec3(0, 0, 1));
        }
    }
}

TEST(PhongAngles, EntityKeysAndAliases) {
    auto entity = [](std::vector<std::pair<std::string, std::string>> pairs) {
        bsp::Entity e;
        e.pairs = std::move(pairs);
        return e;
    };
    EXPECT_EQ(entityShadeAngle(entity({{"classname", "worldspawn"}})), 0.0f);
    EXPECT_EQ(entityShadeAngle(entity({{"_shadeangle", "75"}})), 75.0f);
    EXPECT_EQ(entityShadeAngle(entity({{"_smoothnormals", "30"}})), 30.0f);
    EXPECT_EQ(entityShadeAngle(entity({{"_sn", "45.5"}})), 45.5f);
    EXPECT_EQ(entityShadeAngle(entity({{"_sa", "12"}})), 12.0f);
    EXPECT_EQ(entityShadeAngle(entity({{"_smooth", "60"}})), 60.0f);
    EXPECT_EQ(entityShadeAngle(entity({{"_sn", "20"}, {"_shadeangle", "80"}})), 80.0f);  // _shadeangle first
    EXPECT_EQ(entityShadeAngle(entity({{"_shadeangle", "-5"}})), 0.0f);
    EXPECT_EQ(entityShadeAngle(entity({{"_shadeangle", "abc"}})), 0.0f);

    const std::vector<bsp::Entity> ents{entity({{"classname", "worldspawn"}, {"_sn", "10"}}),
                                        entity({{"classname", "func_door"}, {"model", "*2"}, {"_shadeangle", "70"}}),
                                        entity({{"classname", "func_plat"}, {"model", "*9"}, {"_shadeangle", "20"}})};
    EXPECT_EQ(modelShadeAngles(ents, 3), (std::vector<float>{10, 0, 70}));
}

TEST(PhongAngles, ShaderThenEntityThenDefault) {
    bsp::Bsp b = emptyBsp(1);
    for (int i = 0; i < 4; ++i) addQuad(b, {0, 0, float(i)}, {0, 8, 0}, {8, 0, 0}, 0);
    addModel(b, 0, 2);  // world: surfaces 0, 1
    addModel(b, 2, 2);  // model 1: surfaces 2, 3
    const std::vector<float> angles = surfaceShadeAngles(b, std::vector<float>{80, 0, 80, 0}, std::vector<float>{0, 100}, 120);
    EXPECT_EQ(angles, (std::vector<float>{80, 120, 80, 100}));
    b.surfaces[3].surfaceType = bsp::MST_TRIANGLE_SOUP;
    const std::vector<float> perVertex = vertexShadeAngles(b, angles);
    ASSERT_EQ(perVertex.size(), 16u);
    EXPECT_EQ(perVertex[0], 80.0f);
    EXPECT_EQ(perVertex[4], 120.0f);
    EXPECT_EQ(perVertex[8], 80.0f);
    EXPECT_EQ(perVertex[12], 0.0f);  // triangle soup
}

// A context as loadLightInputs leaves it: BSP, entities, a shader table, options.
std::unique_ptr<LightContext> makeContext(bsp::Bsp b, std::vector<bsp::Entity> entities, std::vector<ShaderInfo> shaders) {
    auto ctx = std::make_unique<LightContext>();
    ctx->bsp = std::move(b);
    ctx->entities = std::move(entities);
    ctx->shaderTable = std::make_unique<ShaderTable>();
    for (ShaderInfo& s : shaders) ctx->shaderTable->add(std::move(s));
    return ctx;
}

ShaderInfo shaderWithAngle(const char* name, float angle) {
    ShaderInfo s = makeImplicitShader(name);
    s.explicitScript = true;
    s.shadeAngleDegrees = angle;
    return s;
}

bsp::Entity makeEntity(std::vector<std::pair<std::string, std::string>> pairs) {
    bsp::Entity e;
    e.pairs = std::move(pairs);
    return e;
}

TEST(PhongStep, OffWithoutShadeEvenWhenShadersAsk) {
    bsp::Bsp b = emptyBsp(1);
    addCorner(b, {0, 0, 0}, 0, 0);
    addModel(b, 0, 2);
    auto ctx = makeContext(b, {makeEntity({{"classname", "worldspawn"}, {"_shadeangle", "100"}})},
                           {shaderWithAngle("textures/phong/s0", 100)});
    buildSurfaceGeometry(*ctx);
    Log log(false);
    smoothNormals(*ctx, log);
    EXPECT_TRUE(ctx->shadedNormals.empty());
}

TEST(PhongStep, ShaderAngleFromTheShaderTable) {
    bsp::Bsp b = emptyBsp(2);
    addCorner(b, {0, 0, 0}, 0, 0);   // shader 0: q3map_shadeAngle 100
    addCorner(b, {500, 0, 0}, 1, 1); // shader 1: no angle
    addModel(b, 0, 4);
    auto ctx = makeContext(b, {makeEntity({{"classname", "worldspawn"}})}, {shaderWithAngle("textures/phong/s0", 100)});
    ctx->options.shade = true;  // bare -shade: default angle 0
    buildSurfaceGeometry(*ctx);
    Log log(false);
    smoothNormals(*ctx, log);
    ASSERT_EQ(ctx->shadedNormals.size(), ctx->bsp.drawVerts.size());
    expectNormal(ctx->shadedNormals[0], {kHalfRoot2, 0, kHalfRoot2}, "shader 0 corner");
    expectNormal(ctx->shadedNormals[8], {0, 0, 1}, "shader 1 floor corner");
    expectNormal(ctx->shadedNormals[12], {1, 0, 0}, "shader 1 wall corner");
    // The BSP keeps its normals.
    expectNormal(Vec3::fromArray(ctx->bsp.drawVerts[0].normal), {0, 0, 1}, "stored normal");

    // -shadeangle 95 gives shader 1 the default; shader 0 keeps its own.
    ctx->options.shadeAngle = 95;
    smoothNormals(*ctx, log);
    expectNormal(ctx->shadedNormals[8], {kHalfRoot2, 0, kHalfRoot2}, "default angle");
    // A shader's own angle wins over the default: 80 breaks the right angle although 95 would not.
    ctx->shaderTable = std::make_unique<ShaderTable>();
    ctx->shaderTable->add(shaderWithAngle("textures/phong/s0", 80));
    smoothNormals(*ctx, log);
    expectNormal(ctx->shadedNormals[0], {0, 0, 1}, "shader 80 beats default 95");
    expectNormal(ctx->shadedNormals[8], {kHalfRoot2, 0, kHalfRoot2}, "default still applies to shader 1");
}

TEST(PhongStep, EntityAngleOfABrushModelWithItsOrigin) {
    // World corner at the origin; brush model 1 holds a corner built at (-200, 0, 0) and an
    // entity origin of (200, 0, 0): in the world it lands exactly on the world corner.
    bsp::Bsp b = emptyBsp(1);
    addCorner(b, {0, 0, 0}, 0, 0);      // surfaces 0, 1 (verts 0..7): world, no angle
    addCorner(b, {-200, 0, 0}, 0, 0);   // surfaces 2, 3 (verts 8..15): model 1
    addModel(b, 0, 2);
    addModel(b, 2, 2);
    auto ctx = makeContext(b,
                           {makeEntity({{"classname", "worldspawn"}}),
                            makeEntity({{"classname", "func_bobbing"}, {"model", "*1"}, {"origin", "200 0 0"},
                                        {"_shadeangle", "100"}})},
                           {});
    ctx->options.shade = true;
    buildSurfaceGeometry(*ctx);
    Log log(false);
    smoothNormals(*ctx, log);
    ASSERT_EQ(ctx->shadedNormals.size(), 16u);
    // The model's own corner smooths (its angle 100); the world's vertices (angle 0) do not join.
    for (int v : {8, 9, 12, 15}) expectNormal(ctx->shadedNormals[v], {kHalfRoot2, 0, kHalfRoot2}, "model corner");
    for (int v : {0, 1}) expectNormal(ctx->shadedNormals[v], {0, 0, 1}, "world floor");
    for (int v : {4, 7}) expectNormal(ctx->shadedNormals[v], {1, 0, 0}, "world wall");

    // Worldspawn with an angle too: vertices of both entities meet in one group (q3map2's light
    // stage smooths across entities); every shared corner takes the same diagonal.
    ctx->entities[0].set("_sn", "100");
    smoothNormals(*ctx, log);
    for (int v : {0, 1, 4, 7, 8, 9, 12, 15})
        expectNormal(ctx->shadedNormals[v], {kHalfRoot2, 0, kHalfRoot2}, "shared corner");

    // A shader angle beats the entity's: 80 breaks the right angle.
    ctx->shaderTable = std::make_unique<ShaderTable>();
    ctx->shaderTable->add(shaderWithAngle("textures/phong/s0", 80));
    smoothNormals(*ctx, log);
    ASSERT_EQ(ctx->shadedNormals.size(), 16u);  // coincident coplanar far edges still group
    for (int v : {0, 1, 8, 9}) expectNormal(ctx->shadedNormals[v], {0, 0, 1}, "floor corner");
    for (int v : {4, 7, 12, 15}) expectNormal(ctx->shadedNormals[v], {1, 0, 0}, "wall corner");
}

}  // namespace
}  // namespace q3::light
