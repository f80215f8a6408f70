// Evaluation of the biquadratic Bezier surface of a control grid: position, attributes and normal.
#include "patch_eval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace q3::patch {
namespace {

struct Basis {
    double b[3];   // quadratic Bernstein weights
    double db[3];  // their derivatives with respect to the local parameter
};

Basis quadraticBasis(double t) {
    const double s = 1.0 - t;
    return {{s * s, 2.0 * t * s, t * t}, {-2.0 * s, 2.0 - 4.0 * t, 2.0 * t}};
}

struct Blend {
    double xyz[3] = {0, 0, 0};
    double du[3] = {0, 0, 0};
    double dv[3] = {0, 0, 0};
    double normal[3] = {0, 0, 0};
    double st[2] = {0, 0};
    double lightmap[2] = {0, 0};
    double color[4] = {0, 0, 0, 0};
};

Blend blendSpan(const ControlGrid& grid, int spanU, double tu, int spanV, double tv) {
    const Basis bu = quadraticBasis(tu);
    const Basis bv = quadraticBasis(tv);
    Blend out;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            const PatchVertex& p = grid.at(2 * spanU + i, 2 * spanV + j);
            const double w = bu.b[i] * bv.b[j];
            const double wu = bu.db[i] * bv.b[j];
            const double wv = bu.b[i] * bv.db[j];
            for (int k = 0; k < 3; ++k) {
                out.xyz[k] += w * p.xyz[k];
                out.du[k] += wu * p.xyz[k];
                out.dv[k] += wv * p.xyz[k];
                out.normal[k] += w * p.normal[k];
            }
            for (int k = 0; k < 2; ++k) {
                out.st[k] += w * p.st[k];
                out.lightmap[k] += w * p.lightmap[k];
            }
            for (int k = 0; k < 4; ++k) out.color[k] += w * p.color[k];
        }
    }
    return out;
}

// Unit cross product of the two tangents, or false when either tangent vanishes or they are
// (nearly) parallel. `scale` is the size of the coordinates: a tangent below a tiny fraction of it is
// rounding noise of a collapsed row or column, whose direction means nothing.
bool tangentNormal(const double du[3], const double dv[3], double scale, Vec3& out) {
    const double n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double lu = std::sqrt(du[0] * du[0] + du[1] * du[1] + du[2] * du[2]);
    const double lv = std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
    const double minTangent = 1e-7 * scale;
    if (!(lu > minTangent) || !(lv > minTangent) || !(len > 1e-6 * lu * lv)) return false;
    out = {float(n[0] / len), float(n[1] / len), float(n[2] / len)};
    return true;
}

double coordinateScale(const Blend& b) {
    return 1.0 + std::max({std::fabs(b.xyz[0]), std::fabs(b.xyz[1]), std::fabs(b.xyz[2])});
}

Vec3 interpolatedNormal(const Blend& b) {
    return normalize(Vec3{float(b.normal[0]), float(b.normal[1]), float(b.normal[2])});
}

// Where the surface is degenerate (a collapsed edge or a cone tip) the tangent plane at a point
// slightly inside the span still gives the limiting normal.
Vec3 surfaceNormal(const ControlGrid& grid, int spanU, double tu, int spanV, double tv, const Blend& b) {
    Vec3 n;
    const double scale = coordinateScale(b);
    if (tangentNormal(b.du, b.dv, scale, n)) return n;
    constexpr double kNudge = 1e-3;
    const double nu = tu < 0.5 ? tu + kNudge : tu - kNudge;
    const double nv = tv < 0.5 ? tv + kNudge : tv - kNudge;
    const double tries[3][2] = {{nu, nv}, {tu, nv}, {nu, tv}};
    for (const auto& t : tries) {
        Blend near = blendSpan(grid, spanU, t[0], spanV, t[1]);
        if (tangentNormal(near.du, near.dv, scale, n)) return n;
    }
    return interpolatedNormal(b);
}

}  // namespace

PatchVertex evaluateSpan(const ControlGrid& grid, int spanU, double tu, int spanV, double tv, NormalSource normals) {
    const Blend b = blendSpan(grid, spanU, tu, spanV, tv);
    PatchVertex v;
    v.xyz = {float(b.xyz[0]), float(b.xyz[1]), float(b.xyz[2])};
    for (int k = 0; k < 2; ++k) {
        v.st[k] = float(b.st[k]);
        v.lightmap[k] = float(b.lightmap[k]);
    }
    for (int k = 0; k < 4; ++k) v.color[k] = float(b.color[k]);
    if (normals == NormalSource::Interpolated) {
        v.normal = interpolatedNormal(b);
        if (v.normal == Vec3{}) v.normal = surfaceNormal(grid, spanU, tu, spanV, tv, b);
    } else {
        v.normal = surfaceNormal(grid, spanU, tu, spanV, tv, b);
    }
    return v;
}

// Splits a whole-grid parameter into (span, local parameter); 1 maps to the end of the last span.
static void splitParameter(float p, int spans, int& span, double& t) {
    const double scaled = std::clamp(double(p), 0.0, 1.0) * spans;
    span = std::min(int(std::floor(scaled)), spans - 1);
    t = scaled - span;
}

PatchVertex evaluate(const ControlGrid& grid, float u, float v) {
    requireValidGrid(grid);
    int su = 0, sv = 0;
    double tu = 0, tv = 0;
    splitParameter(u, (grid.width - 1) / 2, su, tu);
    splitParameter(v, (grid.height - 1) / 2, sv, tv);
    return evaluateSpan(grid, su, tu, sv, tv, NormalSource::Surface);
}

Vec3 evaluatePosition(const ControlGrid& grid, float u, float v) { return evaluate(grid, u, v).xyz; }

bool isValidGrid(const ControlGrid& grid) {
    return grid.width >= 3 && grid.height >= 3 && (grid.width % 2) == 1 && (grid.height % 2) == 1 &&
           grid.points.size() == size_t(grid.width) * size_t(grid.height);
}

void requireValidGrid(const ControlGrid& grid) {
    if (!isValidGrid(grid))
        throw std::invalid_argument("patch control grid " + std::to_string(grid.width) + "x" +
                                    std::to_string(grid.height) + " with " + std::to_string(grid.points.size()) +
                                    " points is not an odd-sized grid of at least 3x3");
}

Bounds controlBounds(const ControlGrid& grid) {
    Bounds b;
    for (const PatchVertex& p : grid.points) b.add(p.xyz);
    return b;
}

}  // namespace q3::patch
