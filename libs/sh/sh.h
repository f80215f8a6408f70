// L2 spherical-harmonics math for the light grid: basis evaluation, projection of light as
// irradiance, evaluation for a normal. Pure functions in double precision; coefficient layout and
// constants are those of sh_constants.h (docs/sh-grid-format.md). No dependencies.
#pragma once

#include <array>
#include <cstddef>

#include "sh_constants.h"
#include "sh_grid_lump.h"

namespace q3::sh {

struct Vec3d {
    double x = 0, y = 0, z = 0;
};

struct Rgb {
    double r = 0, g = 0, b = 0;
};

using Basis = std::array<double, kCoeffCount>;

// Nine RGB coefficients, coefficient-major like the lump: c[i] = {R, G, B}.
struct SH9Color {
    double c[kCoeffCount][3] = {};
};

// Y_i(dir) for a unit direction in BSP axes.
Basis evalBasis(Vec3d dir);
// dir scaled to unit length; (0,0,0) and non-finite input give (0,0,0).
Vec3d normalized(Vec3d dir);

// Irradiance from a directional contribution of `color` arriving from `towardLight` (pointing from
// the sample to the light): adds color * A_l * Y_i(l). Accumulating form for hot loops.
void addDirectionalIrradiance(SH9Color& acc, Vec3d towardLight, Rgb color);
SH9Color projectDirectionalIrradiance(Vec3d towardLight, Rgb color);

// Controlled light model (light-models.md): exact projection of the incidence term
// (1 - w) + w * n.l for n.l > 0, else 0, i.e. factors (1 - w) * H_l + w * A_l.
void addControlledIncidence(SH9Color& acc, Vec3d towardLight, Rgb color, double dotProductWeight);
SH9Color projectControlledIncidence(Vec3d towardLight, Rgb color, double dotProductWeight);

// Uniform ambient: evaluates to exactly `ambient` for every normal.
void addAmbient(SH9Color& acc, Rgb ambient);
SH9Color projectAmbient(Rgb ambient);

SH9Color add(const SH9Color& a, const SH9Color& b);
SH9Color scale(const SH9Color& a, double s);
SH9Color lerp(const SH9Color& a, const SH9Color& b, double t);  // a + (b - a) * t

// sum_i c_i Y_i(n): the irradiance reaching a surface with unit normal n (may be negative from
// ringing); the clamped form is max(0, .) per channel, what shading should use.
Rgb evalIrradiance(const SH9Color& sh, Vec3d normal);
Rgb evalIrradianceClamped(const SH9Color& sh, Vec3d normal);

// Radiance projection, for gathering from cubemaps or ray samples: adds
// weight * radiance * Y_i(dir) (weight = the sample's solid angle, or 4 pi / N for uniform
// sphere samples). The result holds radiance coefficients, not irradiance.
void addRadianceSample(SH9Color& acc, Vec3d dir, Rgb radiance, double weight);
struct RadianceSample {
    Vec3d dir;
    Rgb radiance;
    double weight = 0;
};
SH9Color projectRadianceSamples(const RadianceSample* samples, size_t count);
// Radiance coefficients to irradiance coefficients: multiplies band l by A_l.
SH9Color convolveRadianceToIrradiance(const SH9Color& radiance);

// Conversions to and from the stored (float) lump point.
GridPointSH toGridPoint(const SH9Color& sh);
SH9Color fromGridPoint(const GridPointSH& point);

}  // namespace q3::sh
