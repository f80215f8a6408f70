// Cubemap to L2 SH. The solid angle of a face rectangle follows from integrating the area element
// dA / (1 + u^2 + v^2)^(3/2) of a unit-distance plane, whose antiderivative is
// atan2(u*v, sqrt(u^2 + v^2 + 1)); a texel's solid angle is the inclusion-exclusion of its corners.
// The six faces then sum to exactly 4 pi, so no renormalisation is needed.
#include "sh_cubemap.h"

#include <cmath>

namespace q3::sh {

CubeFaceAxes cubeFaceAxes(CubeFace face) {
    switch (face) {
        case CubeFace::PosX: return {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
        case CubeFace::NegX: return {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
        case CubeFace::PosY: return {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}};
        case CubeFace::NegY: return {{0, -1, 0}, {-1, 0, 0}, {0, 0, -1}};
        case CubeFace::PosZ: return {{0, 0, 1}, {0, -1, 0}, {1, 0, 0}};
        case CubeFace::NegZ: return {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}};
    }
    return {};
}

const char* cubeFaceName(CubeFace face) {
    static constexpr const char* kNames[kCubeFaceCount] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    return kNames[static_cast<int>(face)];
}

double cubeAreaElement(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }

double cubeTexelSolidAngle(int col, int row, int size) {
    const double step = 2.0 / double(size);
    const double u0 = -1.0 + step * col, u1 = u0 + step;
    const double v0 = -1.0 + step * row, v1 = v0 + step;
    return cubeAreaElement(u0, v0) - cubeAreaElement(u0, v1) - cubeAreaElement(u1, v0) + cubeAreaElement(u1, v1);
}

Vec3d cubeTexelDirection(CubeFace face, int col, int row, int size) {
    const CubeFaceAxes a = cubeFaceAxes(face);
    const double u = (2.0 * (col + 0.5)) / double(size) - 1.0;
    const double v = (2.0 * (row + 0.5)) / double(size) - 1.0;
    return normalized({a.outward.x + u * a.right.x + v * a.down.x, a.outward.y + u * a.right.y + v * a.down.y,
                       a.outward.z + u * a.right.z + v * a.down.z});
}

std::string projectCubemap(const Cubemap& faces, SH9Color& out) {
    const int size = faces[0].size;
    for (int f = 0; f < kCubeFaceCount; ++f) {
        const CubeFaceImage& face = faces[size_t(f)];
        const std::string name = cubeFaceName(CubeFace(f));
        if (face.size <= 0) return "face " + name + " is empty";
        if (face.size != size)
            return "face " + name + " is " + std::to_string(face.size) + " texels wide, face +X is " +
                   std::to_string(size) + " (all faces must be the same size)";
        if (face.texels.size() != size_t(size) * size_t(size))
            return "face " + name + " holds " + std::to_string(face.texels.size()) + " texels, expected " +
                   std::to_string(size_t(size) * size_t(size));
    }
    // Solid angles are the same on every face: computed once per texel position.
    std::vector<double> solidAngle(size_t(size) * size_t(size));
    for (int row = 0; row < size; ++row)
        for (int col = 0; col < size; ++col)
            solidAngle[size_t(row) * size_t(size) + size_t(col)] = cubeTexelSolidAngle(col, row, size);
    SH9Color acc;
    for (int f = 0; f < kCubeFaceCount; ++f)
        for (int row = 0; row < size; ++row)
            for (int col = 0; col < size; ++col)
                addRadianceSample(acc, cubeTexelDirection(CubeFace(f), col, row, size), faces[size_t(f)].at(col, row),
                                  solidAngle[size_t(row) * size_t(size) + size_t(col)]);
    out = acc;
    return {};
}

}  // namespace q3::sh
