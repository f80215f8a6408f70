// Projection of a cubemap (six square face images of linear radiance) onto L2 SH radiance, with the
// exact solid angle of every texel, and its convolution to irradiance. Pure functions, no
// dependencies beyond sh.h.
//
// Face convention (BSP axes: X east, Y north, Z up). Each face is seen from the centre of the cube;
// column index grows to the image's right, row index grows downwards (row 0 is the top row), and
// right x down = the face's outward axis:
//
//   face  outward  right  down
//   +X    +X       -Y     -Z
//   -X    -X       +Y     -Z
//   +Y    +Y       +X     -Z
//   -Y    -Y       -X     -Z
//   +Z    +Z       -Y     +X
//   -Z    -Z       -Y     -X
//
// A texel (col, row) of an N x N face covers face coordinates u in [2col/N - 1, 2(col+1)/N - 1] and
// v in [2row/N - 1, 2(row+1)/N - 1]; its direction is outward + u*right + v*down (normalized).
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "sh.h"

namespace q3::sh {

enum class CubeFace { PosX = 0, NegX, PosY, NegY, PosZ, NegZ };
constexpr int kCubeFaceCount = 6;

struct CubeFaceAxes {
    Vec3d outward, right, down;
};
CubeFaceAxes cubeFaceAxes(CubeFace face);
const char* cubeFaceName(CubeFace face);  // "+X", "-X", ...

// One face: size x size texels of linear RGB radiance, row-major, row 0 at the top.
struct CubeFaceImage {
    int size = 0;
    std::vector<Rgb> texels;
    const Rgb& at(int col, int row) const { return texels[size_t(row) * size_t(size) + size_t(col)]; }
};

// Six faces in the order +X -X +Y -Y +Z -Z, all of the same size.
using Cubemap = std::array<CubeFaceImage, kCubeFaceCount>;

// Solid angle of the face rectangle [0, x] x [0, y] at unit distance from the centre of the cube:
// atan2(x*y, sqrt(x^2 + y^2 + 1)). Texel solid angles are differences of four of these.
double cubeAreaElement(double x, double y);
// Exact solid angle of texel (col, row) of an N x N face (the same for every face).
double cubeTexelSolidAngle(int col, int row, int size);
// Unit direction of the centre of texel (col, row) of an N x N face.
Vec3d cubeTexelDirection(CubeFace face, int col, int row, int size);

// sum over texels of radiance * solid angle * Y_i(texel direction): L2 radiance coefficients.
// Returns an empty string on success, otherwise what is wrong with the faces (sizes differ, a face is
// empty, the texel count does not match) and leaves `out` untouched.
std::string projectCubemap(const Cubemap& faces, SH9Color& out);

// Irradiance follows with convolveRadianceToIrradiance (sh.h): band l times A_l.

}  // namespace q3::sh
