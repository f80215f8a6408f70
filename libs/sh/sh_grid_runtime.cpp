#include "sh_grid_runtime.h"

#include <algorithm>
#include <cmath>

#include "sh_bsp_scan.h"
#include "sh_constants.h"
#include "sh_legacy_grid.h"

namespace q3::sh {
namespace {

// Rec. 709 luminance weights: the direction follows what the eye sees, not one channel.
constexpr double kLuminance[3] = {0.2126, 0.7152, 0.0722};

struct AxisSpan {
    int lo = 0, hi = 0;
    double t = 0;  // weight of hi
};

AxisSpan spanAlong(double position, float mins, float cell, int32_t bound) {
    double f = (position - mins) / cell;
    if (!std::isfinite(f)) f = 0;
    f = std::clamp(f, 0.0, double(bound - 1));
    AxisSpan s;
    s.lo = std::min(int(std::floor(f)), std::max(bound - 2, 0));
    s.hi = std::min(s.lo + 1, bound - 1);
    s.t = s.hi == s.lo ? 0.0 : f - s.lo;
    return s;
}

std::string withName(const std::string& name, const std::string& message) {
    return name.empty() ? message : name + ": " + message;
}

}  // namespace

std::string GridRuntime::loadFromBsp(const uint8_t* bsp, size_t size, const std::string& name) {
    grid_ = GridSH{};
    usable_.clear();
    source_ = GridSource::None;

    BspDirectory dir;
    if (std::string err = readBspDirectory(bsp, size, dir); !err.empty()) return withName(name, err);

    ByteRange shLump = dir.lumps[kLumpLightGridSH];
    GridSource shSource = GridSource::Lump18;
    if (shLump.empty()) {
        bool found = false;
        if (std::string err = findBspxLump(bsp, size, dir, kBspxLumpName, shLump, found); !err.empty())
            return withName(name, err);
        shSource = found ? GridSource::Bspx : GridSource::None;
    }
    if (shSource != GridSource::None) {
        GridSH grid;
        std::string err;
        if (!decodeGridLump(shLump.data, shLump.size, grid, err))
            return withName(name, (shSource == GridSource::Bspx ? "BSPX " : "lump 18 ") + err);
        setGrid(std::move(grid), shSource);
        return {};
    }

    const ByteRange& legacy = dir.lumps[kLumpLightGrid];
    if (legacy.empty()) return {};  // no grid at all: source None, engines use their default lighting
    float worldMins[3], worldMaxs[3], gridSize[3];
    if (std::string err = readWorldBounds(dir, worldMins, worldMaxs); !err.empty()) return withName(name, err);
    if (std::string err = readWorldGridSize(dir.lumps[kLumpEntities], gridSize); !err.empty())
        return withName(name, err);
    GridSH grid;
    std::vector<uint8_t> usable;
    if (std::string err = decodeLegacyGrid(legacy, worldMins, worldMaxs, gridSize, grid, usable); !err.empty())
        return withName(name, err);
    grid_ = std::move(grid);
    usable_ = std::move(usable);
    source_ = GridSource::Legacy;
    return {};
}

void GridRuntime::setGrid(GridSH grid, GridSource source) {
    grid_ = std::move(grid);
    usable_.clear();
    source_ = source;
}

GridPointSH GridRuntime::sample(const float position[3]) const {
    GridPointSH out{};
    const int32_t* b = grid_.bounds;
    if (grid_.points.empty() || size_t(b[0]) * size_t(b[1]) * size_t(b[2]) != grid_.points.size()) return out;
    AxisSpan span[3];
    for (int axis = 0; axis < 3; ++axis) span[axis] = spanAlong(position[axis], grid_.mins[axis], grid_.size[axis], b[axis]);

    double sum[9][3] = {};
    double totalWeight = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const int x = (corner & 1) ? span[0].hi : span[0].lo;
        const int y = (corner & 2) ? span[1].hi : span[1].lo;
        const int z = (corner & 4) ? span[2].hi : span[2].lo;
        const double w = ((corner & 1) ? span[0].t : 1 - span[0].t) * ((corner & 2) ? span[1].t : 1 - span[1].t) *
                         ((corner & 4) ? span[2].t : 1 - span[2].t);
        if (w == 0) continue;
        const size_t index = size_t(x) + size_t(y) * b[0] + size_t(z) * b[0] * b[1];
        if (!usable_.empty() && !usable_[index]) continue;
        const GridPointSH& p = grid_.points[index];
        for (int i = 0; i < 9; ++i)
            for (int ch = 0; ch < 3; ++ch) sum[i][ch] += w * p.coeffs[i][ch];
        totalWeight += w;
    }
    if (totalWeight <= 0) return out;
    const double norm = usable_.empty() ? 1.0 : 1.0 / totalWeight;
    for (int i = 0; i < 9; ++i)
        for (int ch = 0; ch < 3; ++ch) out.coeffs[i][ch] = float(sum[i][ch] * norm);
    return out;
}

void irradianceAt(const GridPointSH& sample, const float normal[3], float rgb[3]) {
    float y[kCoeffCount];
    evalBasisInto(normal[0], normal[1], normal[2], y);
    for (int ch = 0; ch < 3; ++ch) {
        float sum = 0;
        for (int i = 0; i < kCoeffCount; ++i) sum += sample.coeffs[i][ch] * y[i];
        rgb[ch] = std::max(0.0f, sum);
    }
}

AmbientCube toAmbientCube(const GridPointSH& sample) {
    static constexpr float kAxes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    AmbientCube cube;
    for (int f = 0; f < 6; ++f) irradianceAt(sample, kAxes[f], cube.face[f]);
    return cube;
}

LegacyLighting toLegacyLighting(const GridPointSH& sample) {
    LegacyLighting out;
    // Linear band: coefficients 1, 2, 3 multiply y, z, x.
    double d[3] = {0, 0, 0};
    for (int ch = 0; ch < 3; ++ch) {
        d[0] += kLuminance[ch] * sample.coeffs[3][ch];
        d[1] += kLuminance[ch] * sample.coeffs[1][ch];
        d[2] += kLuminance[ch] * sample.coeffs[2][ch];
    }
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const bool hasDirection = len > 1e-12 && std::isfinite(len);
    double dir[3] = {0, 0, 1};
    if (hasDirection)
        for (int axis = 0; axis < 3; ++axis) dir[axis] = d[axis] / len;
    for (int axis = 0; axis < 3; ++axis) out.direction[axis] = float(dir[axis]);

    double basis[kCoeffCount];
    evalBasisInto(dir[0], dir[1], dir[2], basis);
    // Normal equations of min over the sphere of (a + k h(n) - E(n))^2, h = max(0, n.dir):
    // [4pi  pi ; pi  2pi/3] [a; k] = [int E; int E h], int E = 2 sqrt(pi) c0,
    // int E h = sum_i A_l c_i Y_i(dir) (Funk-Hecke).
    const double det = 4 * kPi * (2 * kPi / 3) - kPi * kPi;
    for (int ch = 0; ch < 3; ++ch) {
        const double intE = kUniformToCoeff0 * sample.coeffs[0][ch];
        double intEh = 0;
        for (int i = 0; i < kCoeffCount; ++i) intEh += kClampedCosine[kBasis[i].band] * sample.coeffs[i][ch] * basis[i];
        double ambient = ((2 * kPi / 3) * intE - kPi * intEh) / det;
        double directed = (4 * kPi * intEh - kPi * intE) / det;
        if (!hasDirection || directed < 0) {
            directed = 0;
            ambient = intE / (4 * kPi);
        } else if (ambient < 0) {
            ambient = 0;
            directed = intEh / (2 * kPi / 3);
        }
        out.ambient[ch] = float(std::max(0.0, ambient));
        out.directed[ch] = float(std::max(0.0, directed));
    }
    return out;
}

}  // namespace q3::sh
