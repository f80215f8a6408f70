// L2 SH math. Projections use the Funk-Hecke theorem: a kernel symmetric about l projects to
// k_l * Y_i(l), with k_l the kernel's per-band factor from sh_constants.h.
#include "sh.h"

#include <algorithm>
#include <cmath>

namespace q3::sh {
namespace {

void addWithBandFactors(SH9Color& acc, Vec3d dir, Rgb color, const double factors[kBandCount]) {
    const Vec3d l = normalized(dir);
    if (l.x == 0 && l.y == 0 && l.z == 0) return;
    const Basis y = evalBasis(l);
    for (int i = 0; i < kCoeffCount; ++i) {
        const double k = factors[kBasis[i].band] * y[i];
        acc.c[i][0] += color.r * k;
        acc.c[i][1] += color.g * k;
        acc.c[i][2] += color.b * k;
    }
}

}  // namespace

Basis evalBasis(Vec3d dir) {
    Basis out{};
    evalBasisInto(dir.x, dir.y, dir.z, out.data());
    return out;
}

Vec3d normalized(Vec3d v) {
    const double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(len > 0) || !std::isfinite(len)) return {};
    return {v.x / len, v.y / len, v.z / len};
}

void addDirectionalIrradiance(SH9Color& acc, Vec3d towardLight, Rgb color) {
    addWithBandFactors(acc, towardLight, color, kClampedCosine);
}

SH9Color projectDirectionalIrradiance(Vec3d towardLight, Rgb color) {
    SH9Color out;
    addDirectionalIrradiance(out, towardLight, color);
    return out;
}

void addControlledIncidence(SH9Color& acc, Vec3d towardLight, Rgb color, double w) {
    double factors[kBandCount];
    for (int l = 0; l < kBandCount; ++l) factors[l] = (1.0 - w) * kHemisphereStep[l] + w * kClampedCosine[l];
    addWithBandFactors(acc, towardLight, color, factors);
}

SH9Color projectControlledIncidence(Vec3d towardLight, Rgb color, double w) {
    SH9Color out;
    addControlledIncidence(out, towardLight, color, w);
    return out;
}

void addAmbient(SH9Color& acc, Rgb ambient) {
    acc.c[0][0] += ambient.r * kUniformToCoeff0;
    acc.c[0][1] += ambient.g * kUniformToCoeff0;
    acc.c[0][2] += ambient.b * kUniformToCoeff0;
}

SH9Color projectAmbient(Rgb ambient) {
    SH9Color out;
    addAmbient(out, ambient);
    return out;
}

SH9Color add(const SH9Color& a, const SH9Color& b) {
    SH9Color out;
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) out.c[i][ch] = a.c[i][ch] + b.c[i][ch];
    return out;
}

SH9Color scale(const SH9Color& a, double s) {
    SH9Color out;
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) out.c[i][ch] = a.c[i][ch] * s;
    return out;
}

SH9Color lerp(const SH9Color& a, const SH9Color& b, double t) {
    SH9Color out;
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) out.c[i][ch] = a.c[i][ch] + (b.c[i][ch] - a.c[i][ch]) * t;
    return out;
}

Rgb evalIrradiance(const SH9Color& sh, Vec3d normal) {
    const Basis y = evalBasis(normal);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) sum[ch] += sh.c[i][ch] * y[i];
    return {sum[0], sum[1], sum[2]};
}

Rgb evalIrradianceClamped(const SH9Color& sh, Vec3d normal) {
    const Rgb e = evalIrradiance(sh, normal);
    return {std::max(0.0, e.r), std::max(0.0, e.g), std::max(0.0, e.b)};
}

void addRadianceSample(SH9Color& acc, Vec3d dir, Rgb radiance, double weight) {
    const Vec3d d = normalized(dir);
    if (d.x == 0 && d.y == 0 && d.z == 0) return;
    const Basis y = evalBasis(d);
    for (int i = 0; i < kCoeffCount; ++i) {
        const double k = weight * y[i];
        acc.c[i][0] += radiance.r * k;
        acc.c[i][1] += radiance.g * k;
        acc.c[i][2] += radiance.b * k;
    }
}

SH9Color projectRadianceSamples(const RadianceSample* samples, size_t count) {
    SH9Color out;
    for (size_t s = 0; s < count; ++s) addRadianceSample(out, samples[s].dir, samples[s].radiance, samples[s].weight);
    return out;
}

SH9Color convolveRadianceToIrradiance(const SH9Color& radiance) {
    SH9Color out;
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) out.c[i][ch] = radiance.c[i][ch] * kClampedCosine[kBasis[i].band];
    return out;
}

GridPointSH toGridPoint(const SH9Color& sh) {
    GridPointSH p{};
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) p.coeffs[i][ch] = float(sh.c[i][ch]);
    return p;
}

SH9Color fromGridPoint(const GridPointSH& point) {
    SH9Color sh;
    for (int i = 0; i < kCoeffCount; ++i)
        for (int ch = 0; ch < 3; ++ch) sh.c[i][ch] = point.coeffs[i][ch];
    return sh;
}

}  // namespace q3::sh
