// Texture vectors of brush faces for the standard, Valve 220 and brush-primitive forms.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "map_file.h"
#include "texture_projection.h"

using namespace q3;
using namespace q3::map;

namespace {

BrushFace standardFace(float shiftS, float shiftT, float rotate, float scaleS, float scaleT) {
    BrushFace f;
    f.projection = TexProjection::Standard;
    f.standard.shift[0] = shiftS;
    f.standard.shift[1] = shiftT;
    f.standard.rotate = rotate;
    f.standard.scale[0] = scaleS;
    f.standard.scale[1] = scaleT;
    return f;
}

MapPlane planeWithNormal(double x, double y, double z) {
    MapPlane p;
    const double len = std::sqrt(x * x + y * y + z * z);
    p.normal[0] = x / len;
    p.normal[1] = y / len;
    p.normal[2] = z / len;
    return p;
}

}  // namespace

TEST(TextureProjection, StandardFloorProjectsXAndMinusY) {
    const TextureVecs v = textureVectors(standardFace(0, 0, 0, 0.5f, 0.5f), planeWithNormal(0, 0, 1), {64, 64});
    EXPECT_DOUBLE_EQ(v.s({32, -64, 7}), 1.0);
    EXPECT_DOUBLE_EQ(v.t({32, -64, 7}), 2.0);
    // A ceiling uses the same axes.
    const TextureVecs c = textureVectors(standardFace(0, 0, 0, 1, 1), planeWithNormal(0, 0, -1), {128, 32});
    EXPECT_DOUBLE_EQ(c.s({64, 0, 0}), 0.5);
    EXPECT_DOUBLE_EQ(c.t({0, 16, 0}), -0.5);
}

TEST(TextureProjection, StandardWallsRotationScaleAndShift) {
    // A wall facing +x projects y onto S and -z onto T.
    const TextureVecs wall = textureVectors(standardFace(0, 0, 0, 1, 2), planeWithNormal(1, 0, 0), {64, 64});
    EXPECT_DOUBLE_EQ(wall.s({0, 64, 0}), 1.0);
    EXPECT_DOUBLE_EQ(wall.t({0, 0, -128}), 1.0);
    // 90 degrees: on the floor, S follows +y and T follows +x.
    const TextureVecs turned = textureVectors(standardFace(0, 0, 90, 1, 1), planeWithNormal(0, 0, 1), {64, 64});
    EXPECT_DOUBLE_EQ(turned.s({0, 64, 0}), 1.0);
    EXPECT_DOUBLE_EQ(turned.s({64, 0, 0}), 0.0);
    EXPECT_DOUBLE_EQ(turned.t({64, 0, 0}), 1.0);
    // 30 degrees rotates by the exact angle.
    const TextureVecs tilted = textureVectors(standardFace(0, 0, 30, 1, 1), planeWithNormal(0, 0, 1), {64, 64});
    EXPECT_NEAR(tilted.s({64, 0, 0}), std::cos(kPiD / 6), 1e-12);
    // Shifts are in pixels and reduced modulo the image size unless the texture is global.
    const TextureVecs shifted = textureVectors(standardFace(80, -16, 0, 1, 1), planeWithNormal(0, 0, 1), {64, 32});
    EXPECT_DOUBLE_EQ(shifted.vecs[0][3], 16.0 / 64);
    EXPECT_DOUBLE_EQ(shifted.vecs[1][3], 16.0 / 32);
    const TextureVecs global =
        textureVectors(standardFace(80, -16, 0, 1, 1), planeWithNormal(0, 0, 1), {64, 32, true});
    EXPECT_DOUBLE_EQ(global.vecs[0][3], 80.0 / 64);
    EXPECT_DOUBLE_EQ(global.vecs[1][3], -16.0 / 32);
    // Reduced modulo another size (the face's own shader's), then divided by the image's.
    const TextureVecs layered =
        textureVectors(standardFace(80, -16, 0, 1, 1), planeWithNormal(0, 0, 1), {64, 32, false, 128, 128});
    EXPECT_DOUBLE_EQ(layered.vecs[0][3], 80.0 / 64);
    EXPECT_DOUBLE_EQ(layered.vecs[1][3], 112.0 / 32);
    // A zero scale counts as 1.
    const TextureVecs unscaled = textureVectors(standardFace(0, 0, 0, 0, 0), planeWithNormal(0, 0, 1), {64, 64});
    EXPECT_DOUBLE_EQ(unscaled.s({64, 0, 0}), 1.0);
}

TEST(TextureProjection, BaseAxisChoice) {
    Vec3 s, t;
    const double diagonal[3] = {std::sqrt(0.5), std::sqrt(0.5), 0};  // west and south tie: west wins
    textureAxisFromPlane(diagonal, s, t);
    EXPECT_EQ(s, Vec3(0, 1, 0));
    EXPECT_EQ(t, Vec3(0, 0, -1));
    const double south[3] = {0.6, 0.8, 0};
    textureAxisFromPlane(south, s, t);
    EXPECT_EQ(s, Vec3(1, 0, 0));
    const double steepFloor[3] = {0.5, 0.5, std::sqrt(0.5)};
    textureAxisFromPlane(steepFloor, s, t);
    EXPECT_EQ(t, Vec3(0, -1, 0));
}

TEST(TextureProjection, ValveUsesExplicitAxes) {
    BrushFace f;
    f.projection = TexProjection::Valve220;
    f.valve.axis[0] = {0, 1, 0};
    f.valve.axis[1] = {0, 0, -1};
    f.valve.offset[0] = 8;
    f.valve.offset[1] = 0;
    f.valve.scale[0] = 0.5f;
    f.valve.scale[1] = 1;
    const TextureVecs v = textureVectors(f, planeWithNormal(0, 0, 1), {32, 64});
    EXPECT_DOUBLE_EQ(v.s({100, 8, 5}), (8 / 0.5 + 8) / 32);
    EXPECT_DOUBLE_EQ(v.t({0, 0, -64}), 1.0);
}

TEST(TextureProjection, BrushPrimitiveMatrixInPlaneBasis) {
    double s[3], t[3];
    const double up[3] = {0, 0, 1};
    brushPrimitiveAxisBase(up, s, t);
    EXPECT_NEAR(s[0], 0, 1e-12);
    EXPECT_NEAR(s[1], 1, 1e-12);
    EXPECT_NEAR(t[0], 1, 1e-12);
    EXPECT_NEAR(t[2], 0, 1e-12);
    const double wall[3] = {1, 0, 0};
    brushPrimitiveAxisBase(wall, s, t);
    EXPECT_NEAR(s[1], 1, 1e-12);
    EXPECT_NEAR(t[2], -1, 1e-12);

    BrushFace f;
    f.projection = TexProjection::BrushPrimitive;
    f.primitive.matrix[0][0] = 1.0f / 64;
    f.primitive.matrix[0][1] = 0;
    f.primitive.matrix[0][2] = 0.25f;
    f.primitive.matrix[1][0] = 0;
    f.primitive.matrix[1][1] = 1.0f / 128;
    f.primitive.matrix[1][2] = 0;
    // Independent of the image size: no size needed.
    const TextureVecs v = textureVectors(f, planeWithNormal(0, 0, 1), {});
    EXPECT_NEAR(v.s({0, 64, 0}), 1.25, 1e-9);
    EXPECT_NEAR(v.t({128, 0, 0}), 1.0, 1e-9);
}

TEST(TextureProjection, MissingImageSizeIsRejected) {
    EXPECT_THROW(textureVectors(standardFace(0, 0, 0, 1, 1), planeWithNormal(0, 0, 1), {0, 64}), std::invalid_argument);
}
