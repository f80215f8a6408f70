// Texture vectors of brush faces for the three projection forms of the .map format.
#include "texture_projection.h"

#include <cmath>
#include <stdexcept>

namespace q3::map {
namespace {

// Normal of each base plane followed by its S and T axes (floor, ceiling, west, east, south, north).
constexpr double kBaseAxes[6][3][3] = {
    {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  {{0, 0, -1}, {1, 0, 0}, {0, -1, 0}},
    {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}},  {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
};

void requireImage(const TextureImage& image) {
    if (image.width <= 0 || image.height <= 0)
        throw std::invalid_argument("texture projection needs a positive image size, got " +
                                    std::to_string(image.width) + "x" + std::to_string(image.height));
}

// Sine and cosine of a rotation in degrees; the right angles are exact, as in q3map2.
void rotationSinCos(double degrees, double& sinv, double& cosv) {
    if (degrees == 0) { sinv = 0; cosv = 1; }
    else if (degrees == 90) { sinv = 1; cosv = 0; }
    else if (degrees == 180) { sinv = 0; cosv = -1; }
    else if (degrees == 270) { sinv = -1; cosv = 0; }
    else {
        const double radians = degrees / 180.0 * kPiD;
        sinv = std::sin(radians);
        cosv = std::cos(radians);
    }
}

int shiftModulus(int given, int imageSize) { return given > 0 ? given : imageSize; }

TextureVecs standardVectors(const TexStandard& tex, const MapPlane& plane, const TextureImage& image) {
    requireImage(image);
    Vec3 axes[2];
    textureAxisFromPlane(plane.normal, axes[0], axes[1]);
    double vec[2][3] = {{axes[0].x, axes[0].y, axes[0].z}, {axes[1].x, axes[1].y, axes[1].z}};

    double sinv = 0, cosv = 1;
    rotationSinCos(tex.rotate, sinv, cosv);
    // Rotate within the two world axes the base axes use (each base axis has one non-zero part).
    const auto usedAxis = [](const double v[3]) { return v[0] != 0 ? 0 : (v[1] != 0 ? 1 : 2); };
    const int sv = usedAxis(vec[0]);
    const int tv = usedAxis(vec[1]);
    for (auto& v : vec) {
        const double ns = cosv * v[sv] - sinv * v[tv];
        const double nt = sinv * v[sv] + cosv * v[tv];
        v[sv] = ns;
        v[tv] = nt;
    }

    const double scale[2] = {tex.scale[0] != 0 ? tex.scale[0] : 1.0, tex.scale[1] != 0 ? tex.scale[1] : 1.0};
    const int size[2] = {image.width, image.height};
    const int shiftSize[2] = {shiftModulus(image.shiftWidth, image.width), shiftModulus(image.shiftHeight, image.height)};
    TextureVecs out;
    for (int i = 0; i < 2; ++i) {
        double shift = tex.shift[i];
        if (!image.globalTexture) shift -= std::floor(shift / shiftSize[i]) * shiftSize[i];
        for (int j = 0; j < 3; ++j) out.vecs[i][j] = vec[i][j] / scale[i] / size[i];
        out.vecs[i][3] = shift / size[i];
    }
    return out;
}

TextureVecs valveVectors(const TexValve& tex, const TextureImage& image) {
    requireImage(image);
    const int size[2] = {image.width, image.height};
    const int shiftSize[2] = {shiftModulus(image.shiftWidth, image.width), shiftModulus(image.shiftHeight, image.height)};
    TextureVecs out;
    for (int i = 0; i < 2; ++i) {
        const double scale = tex.scale[i] != 0 ? tex.scale[i] : 1.0;
        for (int j = 0; j < 3; ++j) out.vecs[i][j] = tex.axis[i][j] / scale / size[i];
        double shift = tex.offset[i];
        if (!image.globalTexture) shift -= std::floor(shift / shiftSize[i]) * shiftSize[i];
        out.vecs[i][3] = shift / size[i];
    }
    return out;
}

TextureVecs primitiveVectors(const TexBrushPrimitive& tex, const MapPlane& plane) {
    double texS[3], texT[3];
    brushPrimitiveAxisBase(plane.normal, texS, texT);
    TextureVecs out;
    for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 3; ++j) out.vecs[i][j] = tex.matrix[i][0] * texS[j] + tex.matrix[i][1] * texT[j];
        out.vecs[i][3] = tex.matrix[i][2];
    }
    return out;
}

}  // namespace

void textureAxisFromPlane(const double normal[3], Vec3& sAxis, Vec3& tAxis) {
    // The small margin keeps 45-degree faces on the earlier axis despite rounding in the normal.
    double best = 0;
    int bestAxis = 0;
    for (int i = 0; i < 6; ++i) {
        const double* n = kBaseAxes[i][0];
        const double d = normal[0] * n[0] + normal[1] * n[1] + normal[2] * n[2];
        if (d > best + 0.0001) {
            best = d;
            bestAxis = i;
        }
    }
    const auto& a = kBaseAxes[bestAxis];
    sAxis = {float(a[1][0]), float(a[1][1]), float(a[1][2])};
    tAxis = {float(a[2][0]), float(a[2][1]), float(a[2][2])};
}

void brushPrimitiveAxisBase(const double normal[3], double texS[3], double texT[3]) {
    double n[3];
    for (int i = 0; i < 3; ++i) n[i] = std::fabs(normal[i]) < 1e-6 ? 0.0 : normal[i];
    // Rotations about y then z that carry +x onto the normal; texS and texT are +y and +z carried
    // along (texT flipped to point down the texture's T direction).
    const double rotY = -std::atan2(n[2], std::sqrt(n[0] * n[0] + n[1] * n[1]));
    const double rotZ = std::atan2(n[1], n[0]);
    texS[0] = -std::sin(rotZ);
    texS[1] = std::cos(rotZ);
    texS[2] = 0;
    texT[0] = -std::sin(rotY) * std::cos(rotZ);
    texT[1] = -std::sin(rotY) * std::sin(rotZ);
    texT[2] = -std::cos(rotY);
}

TextureVecs textureVectors(const BrushFace& face, const MapPlane& plane, const TextureImage& image) {
    switch (face.projection) {
        case TexProjection::Standard: return standardVectors(face.standard, plane, image);
        case TexProjection::Valve220: return valveVectors(face.valve, image);
        case TexProjection::BrushPrimitive: return primitiveVectors(face.primitive, plane);
    }
    return {};
}

}  // namespace q3::map
