// The comparator on small synthetic BSPs: identity, scaling, packing independence, one-sided
// lightmaps, vertex colours, classes, external pages and malformed input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "file_io.h"
#include "image.h"
#include "light_compare.h"
#include "test_data.h"

namespace q3::conformance {
namespace {

constexpr int kPage = 128;
constexpr int kBlock = 16;  // texels per surface block; st covers the inner 14 so filtering stays inside

struct Scene {
    bsp::Bsp bsp;
    std::vector<uint8_t> lump;  // lump 14

    void ensurePages(int count) {
        if (lump.size() < size_t(count) * bsp::kLightmapPageBytes) lump.resize(size_t(count) * bsp::kLightmapPageBytes, 0);
    }
    void paint(int page, int bx, int by, uint8_t r, uint8_t g, uint8_t b) {
        ensurePages(page + 1);
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
            for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
                uint8_t* t = &lump[size_t(page) * bsp::kLightmapPageBytes + (size_t(y) * kPage + x) * 3];
                t[0] = r;
                t[1] = g;
                t[2] = b;
            }
    }
    LitBsp lit(const std::string& name) const {
        LitBsp l;
        l.name = name;
        l.bsp = bsp;
        l.bsp.lightmaps = lump;
        l.pages = pagesFromLump(lump, name);
        return l;
    }
};

// Lightmap st of a point (u, v in 0..1 across the block's inner 14x14 texels).
void blockSt(int bx, int by, float u, float v, float* st) {
    st[0] = (bx * kBlock + 1 + u * (kBlock - 2)) / float(kPage);
    st[1] = (by * kBlock + 1 + v * (kBlock - 2)) / float(kPage);
}

bsp::DrawVert vertex(Vec3 p, Vec3 n, int bx, int by, float u, float v) {
    bsp::DrawVert dv{};
    p.toArray(dv.xyz);
    n.toArray(dv.normal);
    blockSt(bx, by, u, v, dv.lightmap);
    dv.color[0] = dv.color[1] = dv.color[2] = 100;
    dv.color[3] = 255;
    return dv;
}

int addShader(Scene& s, const char* name) {
    bsp::Shader sh{};
    std::strncpy(sh.name, name, sizeof sh.name - 1);
    sh.contentFlags = 1;
    s.bsp.shaders.push_back(sh);
    return int(s.bsp.shaders.size()) - 1;
}

// A planar square of side `size` at `origin` (facing +z), lightmapped on block (bx, by) of `page`.
int addQuad(Scene& s, Vec3 origin, float size, int page, int bx, int by) {
    bsp::Surface surf{};
    surf.shaderNum = 0;
    surf.fogNum = -1;
    surf.surfaceType = bsp::MST_PLANAR;
    surf.firstVert = int(s.bsp.drawVerts.size());
    surf.numVerts = 4;
    surf.firstIndex = int(s.bsp.drawIndexes.size());
    surf.numIndexes = 6;
    surf.lightmapNum = page;
    const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& c : corners)
        s.bsp.drawVerts.push_back(vertex(origin + Vec3{c[0] * size, c[1] * size, 0}, {0, 0, 1}, bx, by, c[0], c[1]));
    for (int i : {0, 1, 2, 0, 2, 3}) s.bsp.drawIndexes.push_back(i);
    s.bsp.surfaces.push_back(surf);
    return int(s.bsp.surfaces.size()) - 1;
}

// A flat 3x3 patch control grid.
int addPatch(Scene& s, Vec3 origin, float size, int page, int bx, int by) {
    bsp::Surface surf{};
    surf.fogNum = -1;
    surf.surfaceType = bsp::MST_PATCH;
    surf.firstVert = int(s.bsp.drawVerts.size());
    surf.numVerts = 9;
    surf.lightmapNum = page;
    surf.patchWidth = surf.patchHeight = 3;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            s.bsp.drawVerts.push_back(vertex(origin + Vec3{col * size / 2, row * size / 2, 0}, {0, 0, 1}, bx, by,
                                             col / 2.0f, row / 2.0f));
    s.bsp.surfaces.push_back(surf);
    return int(s.bsp.surfaces.size()) - 1;
}

// Three quads and a patch, each with its own brightness: 40, 80, 160 (grey) and 200 (red).
Scene baseScene() {
    Scene s;
    addShader(s, "textures/test/wall");
    addQuad(s, {0, 0, 0}, 64, 0, 0, 0);
    addQuad(s, {0, 200, 0}, 64, 0, 1, 0);
    addQuad(s, {0, 400, 0}, 128, 0, 2, 0);
    addPatch(s, {0, 600, 0}, 64, 0, 3, 0);
    s.paint(0, 0, 0, 40, 40, 40);
    s.paint(0, 1, 0, 80, 80, 80);
    s.paint(0, 2, 0, 160, 160, 160);
    s.paint(0, 3, 0, 200, 0, 0);
    return s;
}

double classRatio(const Comparison& c, const std::string& name) {
    for (const ClassFigures& k : c.lightmaps.classes)
        if (k.name == name) return k.ratio;
    ADD_FAILURE() << "no class " << name;
    return 0;
}

const ClassFigures& classOf(const Comparison& c, const std::string& name) {
    for (const ClassFigures& k : c.lightmaps.classes)
        if (k.name == name) return k;
    throw std::runtime_error("no class " + name);
}

TEST(LightCompare, IdenticalInputsGiveRatioAndCorrelationOne) {
    const Scene s = baseScene();
    const Comparison c = compareLitBsps(s.lit("ref"), s.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(c.lightmaps.referenceLit, 4);
    EXPECT_EQ(c.lightmaps.bothLit, 4);
    EXPECT_EQ(c.lightmaps.referenceOnly + c.lightmaps.oursOnly, 0);
    EXPECT_NEAR(c.lightmaps.ratio, 1.0, 1e-12);
    EXPECT_NEAR(c.lightmaps.correlation, 1.0, 1e-12);
    EXPECT_NEAR(classRatio(c, "planar"), 1.0, 1e-12);
    EXPECT_NEAR(classRatio(c, "patch"), 1.0, 1e-12);
    EXPECT_EQ(classOf(c, "patch").surfaces, 1);
    EXPECT_EQ(classOf(c, "planar").surfaces, 3);
    EXPECT_FALSE(classOf(c, "near-light").measured);
    EXPECT_TRUE(std::isnan(classRatio(c, "near-light")));
}

TEST(LightCompare, SurfaceMeanIsTheLuminanceOfItsTexels) {
    const Scene s = baseScene();
    const LitBsp lit = s.lit("ref");
    EXPECT_NEAR(sampleSurface(lit, 0).mean, 40, 1e-3);
    EXPECT_NEAR(sampleSurface(lit, 2).mean, 160, 1e-3);
    EXPECT_NEAR(sampleSurface(lit, 3).mean, 0.299 * 200, 1e-3);  // red: Rec. 601 luminance
    EXPECT_NEAR(sampleSurface(lit, 2).area, 128.0 * 128, 1e-3);
    EXPECT_TRUE(sampleSurface(lit, 3).lit);
}

TEST(LightCompare, MeanIsAreaWeightedOverALinearGradient) {
    // A gradient along x across the block: the mean over the inner texels is the midpoint value.
    Scene s;
    addShader(s, "textures/test/wall");
    addQuad(s, {0, 0, 0}, 64, 0, 0, 0);
    s.ensurePages(1);
    for (int y = 0; y < kBlock; ++y)
        for (int x = 0; x < kBlock; ++x)
            for (int c = 0; c < 3; ++c) s.lump[(size_t(y) * kPage + x) * 3 + c] = uint8_t(10 * x);
    // st runs from texel coordinate 1 to 15, i.e. texel-centre positions 0.5 .. 14.5: mean 7.5 texels = 75.
    EXPECT_NEAR(sampleSurface(s.lit("ref"), 0).mean, 75, 0.05);
}

TEST(LightCompare, HalvedLightmapGivesHalfTheRatio) {
    const Scene ref = baseScene();
    Scene ours = ref;
    for (uint8_t& b : ours.lump) b = uint8_t(b / 2);  // every painted value is even: exact halves
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_NEAR(c.lightmaps.ratio, 0.5, 1e-9);
    EXPECT_NEAR(c.lightmaps.correlation, 1.0, 1e-9);
    for (const ClassFigures& k : c.lightmaps.classes) {
        if (k.measured && k.surfaces > 0) {
            EXPECT_NEAR(k.ratio, 0.5, 1e-9) << k.name;
        }
    }
}

TEST(LightCompare, SwappedPageLayoutWithTheSameTexelsGivesOne) {
    const Scene ref = baseScene();
    Scene ours = ref;
    // Ours packs surface 0 on a second page at block (5, 6) and swaps surfaces 1 and 2.
    ours.lump.assign(bsp::kLightmapPageBytes * 2, 0);
    ours.paint(1, 5, 6, 40, 40, 40);
    ours.paint(0, 2, 0, 80, 80, 80);
    ours.paint(0, 1, 0, 160, 160, 160);
    ours.paint(0, 3, 0, 200, 0, 0);
    auto moveSurface = [&](int surface, int page, int bx, int by) {
        bsp::Surface& surf = ours.bsp.surfaces[surface];
        surf.lightmapNum = page;
        const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k < 4; ++k) blockSt(bx, by, corners[k][0], corners[k][1], ours.bsp.drawVerts[surf.firstVert + k].lightmap);
    };
    moveSurface(0, 1, 5, 6);
    moveSurface(1, 0, 2, 0);
    moveSurface(2, 0, 1, 0);
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(c.lightmaps.oursPages, 2);
    EXPECT_NEAR(c.lightmaps.ratio, 1.0, 1e-9);
    EXPECT_NEAR(c.lightmaps.correlation, 1.0, 1e-9);
    for (const SurfaceFigures& w : c.lightmaps.worst) EXPECT_NEAR(w.mismatch, 0, 1e-9) << w.surface;
}

TEST(LightCompare, OursWithoutLightmapsIsReportedNotFatal) {
    const Scene ref = baseScene();
    Scene ours = ref;
    ours.lump.clear();
    for (bsp::Surface& surf : ours.bsp.surfaces) surf.lightmapNum = bsp::kLightmapByVertex;
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(c.lightmaps.oursLit, 0);
    EXPECT_EQ(c.lightmaps.referenceOnly, 4);
    EXPECT_EQ(c.lightmaps.ratio, 0.0);
    EXPECT_TRUE(std::isnan(c.lightmaps.correlation));
    ASSERT_FALSE(c.lightmaps.worst.empty());
    EXPECT_FALSE(c.lightmaps.worst[0].oursLit);
    bool noted = false;
    for (const std::string& n : c.notes) noted = noted || n.find("ours wrote no lightmaps") != std::string::npos;
    EXPECT_TRUE(noted);
    EXPECT_NE(toJson(c).find("\"correlation\": null"), std::string::npos);
    EXPECT_NE(toText(c).find("reference only 4"), std::string::npos);
}

TEST(LightCompare, OneSidedSurfacesCountedBothWaysAndListedFirst) {
    Scene ref = baseScene();
    Scene ours = ref;
    ref.bsp.surfaces[1].lightmapNum = bsp::kLightmapByVertex;   // ours only
    ours.bsp.surfaces[2].lightmapNum = bsp::kLightmapByVertex;  // reference only
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(c.lightmaps.referenceOnly, 1);
    EXPECT_EQ(c.lightmaps.oursOnly, 1);
    EXPECT_EQ(c.lightmaps.bothLit, 2);
    // Reference sum 40 + 160 + 59.8; ours lacks the 160.
    const double red = 0.299 * 200;
    EXPECT_NEAR(c.lightmaps.ratio, (40 + red) / (40 + 160 + red), 1e-6);
    ASSERT_GE(c.lightmaps.worst.size(), 2u);
    EXPECT_NE(c.lightmaps.worst[0].referenceLit, c.lightmaps.worst[0].oursLit);
    EXPECT_NE(c.lightmaps.worst[1].referenceLit, c.lightmaps.worst[1].oursLit);
}

TEST(LightCompare, ClassesFollowLightsShadowAndAreaEmitters) {
    Scene ref = baseScene();
    addShader(ref, "textures/test/lamp");
    ref.bsp.surfaces[2].shaderNum = 1;  // the 128-unit quad at y = 400 emits area light
    Scene ours = ref;
    ours.paint(0, 0, 0, 20, 20, 20);  // surface 0 (dark, at the origin) comes out half as bright
    ClassInputs classes;
    classes.lightsKnown = true;
    classes.lightOrigins = {{32, 32, 100}};  // 100 units above surface 0 only
    classes.shadersKnown = true;
    classes.shaderEmitsArea = {false, true};
    classes.shaderIsSky = {false, false};
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, classes);
    EXPECT_EQ(classOf(c, "near-light").surfaces, 1);
    EXPECT_NEAR(classRatio(c, "near-light"), 0.5, 1e-6);
    // Median of 40, 59.8, 80, 160 is 80: below 20 only... none; 40 is not below 25 % of 80.
    EXPECT_EQ(classOf(c, "shadow").surfaces, 0);
    // Within 256 units of the lamp quad (y 400..528): surface 1 (y 200..264) and the lamp itself,
    // and the patch at y 600.
    EXPECT_EQ(classOf(c, "area-lit").surfaces, 3);
    EXPECT_NEAR(classRatio(c, "area-lit"), 1.0, 1e-9);
    EXPECT_TRUE(classOf(c, "sky-lit").measured);
    EXPECT_EQ(classOf(c, "sky-lit").surfaces, 0);
    EXPECT_EQ(c.lightmaps.worst[0].surface, 0);
}

TEST(LightCompare, ShadowClassIsBelowAQuarterOfTheMedian) {
    Scene ref = baseScene();
    ref.paint(0, 0, 0, 10, 10, 10);  // 10 < 0.25 * median (80)
    const Comparison c = compareLitBsps(ref.lit("ref"), ref.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(classOf(c, "shadow").surfaces, 1);
}

TEST(LightCompare, SkyLitSurfacesSeeASkySurfaceStraightUp) {
    Scene ref = baseScene();
    addShader(ref, "textures/test/sky");
    ref.bsp.shaders[1].surfaceFlags = 0x4;  // sky
    // A sky quad 500 units above surface 1 and a roof quad above surface 0.
    const int sky = addQuad(ref, {-10, 190, 500}, 90, 0, 7, 7);
    ref.bsp.surfaces[sky].shaderNum = 1;
    ref.bsp.surfaces[sky].lightmapNum = bsp::kLightmapNone;
    const int roof = addQuad(ref, {-10, -10, 200}, 90, 0, 7, 7);
    ref.bsp.surfaces[roof].lightmapNum = bsp::kLightmapNone;
    const int skyAboveRoof = addQuad(ref, {-10, -10, 500}, 90, 0, 7, 7);
    ref.bsp.surfaces[skyAboveRoof].shaderNum = 1;
    ref.bsp.surfaces[skyAboveRoof].lightmapNum = bsp::kLightmapNone;
    ClassInputs classes;
    classes.shadersKnown = true;
    classes.shaderEmitsArea = {false, false};
    classes.shaderIsSky = {false, true};
    classes.skyEmits = true;
    const Comparison c = compareLitBsps(ref.lit("ref"), ref.lit("ours"), nullptr, classes);
    EXPECT_EQ(classOf(c, "sky-lit").surfaces, 1);  // surface 1; surface 0 is under the roof
    EXPECT_NEAR(classOf(c, "sky-lit").referenceSum, 80.0 * 64 * 64, 1e-3);  // mean x area
}

TEST(LightCompare, SurfacesTheReferenceDoesNotRepeatAreSetApart) {
    const Scene ref = baseScene();
    Scene ref2 = ref;
    ref2.paint(0, 2, 0, 100, 100, 100);  // surface 2: 160 in one reference run, 100 in the other
    Scene ours = ref;
    ours.paint(0, 2, 0, 20, 20, 20);  // ours differs there only
    ours.paint(0, 1, 0, 82, 82, 82);  // and by 2 % on surface 1
    const LitBsp second = ref2.lit("ref2");
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), &second, ClassInputs{});
    EXPECT_EQ(c.lightmaps.repeatable, 3);
    const double red = 0.299 * 200;
    EXPECT_NEAR(c.lightmaps.repeatableRatio, (40 + 82 + red) / (40 + 80 + red), 1e-6);
    EXPECT_LT(c.lightmaps.ratio, 0.7);
    ASSERT_FALSE(c.lightmaps.worst.empty());
    EXPECT_EQ(c.lightmaps.worst[0].surface, 2);
    EXPECT_FALSE(c.lightmaps.worst[0].referenceRepeats);
    EXPECT_NE(toText(c).find(" ~"), std::string::npos);
    // Classes leave surface 2 out: planar holds surfaces 0 and 1 only.
    EXPECT_EQ(classOf(c, "planar").surfaces, 2);
    EXPECT_NEAR(classRatio(c, "planar"), (40.0 + 82) / (40 + 80), 1e-6);
    const Comparison without = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(without.lightmaps.repeatable, -1);
}

TEST(LightCompare, ClassesWeighSurfacesByArea) {
    // A 2x2-unit sliver three times too bright beside a 64x64 wall that matches: the planar class
    // moves by the sliver's share of the area, not by a third.
    Scene ref;
    addShader(ref, "textures/test/wall");
    addQuad(ref, {0, 0, 0}, 64, 0, 0, 0);
    addQuad(ref, {0, 200, 0}, 2, 0, 1, 0);
    ref.paint(0, 0, 0, 40, 40, 40);
    ref.paint(0, 1, 0, 40, 40, 40);
    Scene ours = ref;
    ours.paint(0, 1, 0, 120, 120, 120);
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_NEAR(classRatio(c, "planar"), (40.0 * 4096 + 120.0 * 4) / (40.0 * 4096 + 40.0 * 4), 1e-6);
    EXPECT_NEAR(c.lightmaps.ratio, (40.0 + 120) / (40 + 40), 1e-6);  // the total stays per surface
}

// A tree of one node, the plane z = 32: above it open space (cluster 0), below it a solid leaf.
void addSolidBelow(Scene& s, float height) {
    s.bsp.planes.push_back(bsp::Plane{{0, 0, 1}, height});
    s.bsp.nodes.push_back(bsp::Node{0, {-1, -2}, {0, 0, 0}, {0, 0, 0}});
    bsp::Leaf open{};
    open.cluster = 0;
    bsp::Leaf solid{};
    solid.cluster = -1;
    s.bsp.leafs = {open, solid};
}

TEST(LightCompare, TexelsAgainstSolidAreLeftOut) {
    // Surface 0 lies under the solid (its texels face a wall flush against them), surface 1 above.
    Scene ref;
    addShader(ref, "textures/test/wall");
    addQuad(ref, {0, 0, 0}, 64, 0, 0, 0);
    addQuad(ref, {0, 0, 64}, 64, 0, 1, 0);
    addPatch(ref, {0, 0, 0}, 64, 0, 2, 0);  // flat: tested as planar surfaces are
    addSolidBelow(ref, 32);
    ref.paint(0, 0, 0, 40, 40, 40);
    ref.paint(0, 1, 0, 80, 80, 80);
    ref.paint(0, 2, 0, 60, 60, 60);
    Scene ours = ref;
    ours.paint(0, 0, 0, 200, 200, 200);  // differs only where nobody looks
    ours.paint(0, 2, 0, 10, 10, 10);
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(c.lightmaps.hiddenSurfaces, 2);
    EXPECT_NEAR(c.lightmaps.ratio, 1.0, 1e-9);
    EXPECT_EQ(classOf(c, "planar").surfaces, 1);
    EXPECT_EQ(classOf(c, "patch").surfaces, 0);
    EXPECT_NE(toText(c).find("entirely against solid"), std::string::npos);
    CompareOptions everything;
    everything.leaveOutHidden = false;
    const Comparison all = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{}, everything);
    EXPECT_EQ(all.lightmaps.hiddenSurfaces, 0);
    EXPECT_NEAR(all.lightmaps.ratio, (200.0 + 80 + 10) / (40 + 80 + 60), 1e-6);
    // Half under the solid: the mean is the visible half's.
    Scene half;
    addShader(half, "textures/test/wall");
    bsp::Surface wall{};
    wall.fogNum = -1;
    wall.surfaceType = bsp::MST_PLANAR;
    wall.numVerts = 4;
    wall.numIndexes = 6;
    const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& k : corners)  // a wall facing +y from z = 0 to 64, its lightmap bright above z = 32
        half.bsp.drawVerts.push_back(vertex({k[0] * 64, 0, k[1] * 64}, {0, 1, 0}, 0, 0, k[0], k[1]));
    for (int i : {0, 1, 2, 0, 2, 3}) half.bsp.drawIndexes.push_back(i);
    half.bsp.surfaces.push_back(wall);
    addSolidBelow(half, 32);
    half.ensurePages(1);
    for (int y = 0; y < kBlock; ++y)
        for (int x = 0; x < kBlock; ++x)
            for (int ch = 0; ch < 3; ++ch) half.lump[(size_t(y) * kPage + x) * 3 + ch] = y >= kBlock / 2 ? 100 : 0;
    const SurfaceSample visible = sampleSurface(half.lit("half"), 0, nullptr);
    EXPECT_NEAR(visible.mean, 50, 3);
    const Comparison h = compareLitBsps(half.lit("ref"), half.lit("ours"), nullptr, ClassInputs{});
    ASSERT_FALSE(h.lightmaps.worst.empty());
    EXPECT_NEAR(h.lightmaps.worst[0].referenceMean, 100, 8);
    EXPECT_NEAR(h.lightmaps.worst[0].area, 64 * 32, 64 * 4);
}

TEST(LightCompare, VertexColoursOfVertexLitSurfaces) {
    Scene ref = baseScene();
    ref.bsp.surfaces[1].lightmapNum = bsp::kLightmapByVertex;
    Scene ours = ref;
    for (int i = 0; i < 4; ++i) {
        bsp::DrawVert& v = ours.bsp.drawVerts[ours.bsp.surfaces[1].firstVert + i];
        v.color[0] = v.color[1] = v.color[2] = uint8_t(50 + 50 * i);
        ref.bsp.drawVerts[ref.bsp.surfaces[1].firstVert + i].color[0] = uint8_t(25 + 25 * i);
        ref.bsp.drawVerts[ref.bsp.surfaces[1].firstVert + i].color[1] = uint8_t(25 + 25 * i);
        ref.bsp.drawVerts[ref.bsp.surfaces[1].firstVert + i].color[2] = uint8_t(25 + 25 * i);
    }
    const Comparison c = compareLitBsps(ref.lit("ref"), ours.lit("ours"), nullptr, ClassInputs{});
    EXPECT_EQ(c.vertexes.surfaces, 1);
    EXPECT_EQ(c.vertexes.vertexes, 4);
    EXPECT_NEAR(c.vertexes.ratio, 2.0, 1e-12);
    EXPECT_NEAR(c.vertexes.correlation, 1.0, 1e-9);
}

TEST(LightCompare, DifferentInputIsAnErrorNamingOurs) {
    const Scene ref = baseScene();
    Scene ours = ref;
    ours.bsp.surfaces.pop_back();
    try {
        compareLitBsps(ref.lit("ref.bsp"), ours.lit("ours.bsp"), nullptr, ClassInputs{});
        FAIL() << "no error";
    } catch (const bsp::BspError& e) {
        EXPECT_NE(std::string(e.what()).find("ours.bsp"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("surfaces"), std::string::npos) << e.what();
    }
    Scene badPage = ref;
    badPage.bsp.surfaces[0].lightmapNum = 9;
    EXPECT_THROW(compareLitBsps(ref.lit("ref.bsp"), badPage.lit("ours.bsp"), nullptr, ClassInputs{}), bsp::BspError);
    EXPECT_THROW(pagesFromLump(std::vector<uint8_t>(100), "x.bsp"), bsp::BspError);
}

TEST(LightCompare, ExternalPagesAreReadBesideTheBsp) {
    const std::filesystem::path dir = test::tempDir();
    const Scene scene = baseScene();
    bsp::Bsp internal = scene.bsp;
    internal.lightmaps = scene.lump;
    bsp::writeBsp(dir / "internal.bsp", internal);
    bsp::writeBsp(dir / "ext.bsp", scene.bsp);  // lump 14 empty
    // Before the pages exist: a one-line error naming the BSP and the missing file.
    try {
        loadLitBsp(dir / "ext.bsp");
        FAIL() << "no error";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("lm_0000.tga"), std::string::npos) << e.what();
    }
    Image page;
    page.width = page.height = kPage;
    page.rgba.resize(size_t(kPage) * kPage * 4);
    for (size_t i = 0; i < size_t(kPage) * kPage; ++i) {
        for (int c = 0; c < 3; ++c) page.rgba[i * 4 + c] = scene.lump[i * 3 + c];
        page.rgba[i * 4 + 3] = 255;
    }
    std::filesystem::create_directories(dir / "ext");
    writeFileAtomic(dir / "ext" / "lm_0000.tga", encodeTga(page, false));
    const LitBsp ext = loadLitBsp(dir / "ext.bsp");
    EXPECT_TRUE(ext.externalPages);
    const LitBsp in = loadLitBsp(dir / "internal.bsp");
    EXPECT_FALSE(in.externalPages);
    const Comparison c = compareLitBsps(in, ext, nullptr, ClassInputs{});
    EXPECT_NEAR(c.lightmaps.ratio, 1.0, 1e-9);
    EXPECT_NEAR(c.lightmaps.correlation, 1.0, 1e-9);
}

TEST(LightCompare, JsonHasEverySection) {
    const Scene s = baseScene();
    const std::string json = toJson(compareLitBsps(s.lit("r\"ef"), s.lit("ours"), nullptr, ClassInputs{}));
    for (const char* key : {"\"lightmaps\"", "\"classes\"", "\"worst\"", "\"vertexes\"", "\"grid\"", "\"notes\"",
                            "\"agreed\": null", "r\\\"ef"})
        EXPECT_NE(json.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace q3::conformance
