#include "sh_test_support.h"

#include <cmath>
#include <cstring>

namespace q3::sh::test {

void gaussLegendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(n, 0);
    weights.assign(n, 0);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double dp = 0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::fabs(dx) < 1e-16) break;
        }
        nodes[i] = 0.5 * (b - a) * x + 0.5 * (b + a);
        weights[i] = (b - a) / ((1 - x * x) * dp * dp);
    }
}

double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

std::vector<WeightedDir> capQuadrature(Vec3d pole, double cosMin, double cosMax, int cosNodes, int azimuthNodes) {
    const Vec3d w = normalized(pole);
    const Vec3d helper = std::fabs(w.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    Vec3d u{helper.y * w.z - helper.z * w.y, helper.z * w.x - helper.x * w.z, helper.x * w.y - helper.y * w.x};
    u = normalized(u);
    const Vec3d v{w.y * u.z - w.z * u.y, w.z * u.x - w.x * u.z, w.x * u.y - w.y * u.x};
    std::vector<double> cosines, cosWeights;
    gaussLegendre(cosNodes, cosMin, cosMax, cosines, cosWeights);
    std::vector<WeightedDir> out;
    for (int i = 0; i < cosNodes; ++i) {
        const double c = cosines[i];
        const double s = std::sqrt(std::max(0.0, 1 - c * c));
        for (int j = 0; j < azimuthNodes; ++j) {
            const double phi = 2 * kPi * (j + 0.5) / azimuthNodes;
            const double a = s * std::cos(phi), b = s * std::sin(phi);
            out.push_back({{a * u.x + b * v.x + c * w.x, a * u.y + b * v.y + c * w.y, a * u.z + b * v.z + c * w.z},
                           cosWeights[i] * 2 * kPi / azimuthNodes});
        }
    }
    return out;
}

std::vector<WeightedDir> sphereQuadrature(int cosNodes, int azimuthNodes) {
    return capQuadrature({0, 0, 1}, -1, 1, cosNodes, azimuthNodes);
}

std::vector<Vec3d> fibonacciSphere(int count) {
    std::vector<Vec3d> out;
    const double golden = kPi * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double z = 1 - (2 * i + 1.0) / count;
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        out.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    return out;
}

Vec3d randomDirection(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, 2 * kPi);
    const double z = unit(rng);
    const double phi = angle(rng);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

void putU32(std::vector<uint8_t>& bytes, size_t at, uint32_t value) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = uint8_t(value >> (8 * i));
}

void putF32(std::vector<uint8_t>& bytes, size_t at, float value) {
    uint32_t u;
    std::memcpy(&u, &value, 4);
    putU32(bytes, at, u);
}

void appendF32(std::vector<uint8_t>& bytes, float value) {
    bytes.resize(bytes.size() + 4);
    putF32(bytes, bytes.size() - 4, value);
}

std::vector<uint8_t> buildBsp(int version, int lumpCount, const std::vector<std::vector<uint8_t>>& lumps,
                              const std::vector<BspxEntry>& bspx) {
    std::vector<uint8_t> out(8 + 8 * size_t(lumpCount), 0);
    std::memcpy(out.data(), "IBSP", 4);
    putU32(out, 4, uint32_t(version));
    for (int i = 0; i < lumpCount && i < int(lumps.size()); ++i) {
        if (lumps[i].empty()) continue;
        out.resize((out.size() + 3) & ~size_t(3), 0);
        putU32(out, 8 + 8 * i, uint32_t(out.size()));
        putU32(out, 12 + 8 * i, uint32_t(lumps[i].size()));
        out.insert(out.end(), lumps[i].begin(), lumps[i].end());
    }
    if (!bspx.empty()) {
        out.resize((out.size() + 3) & ~size_t(3), 0);
        const size_t dirStart = out.size();
        out.resize(dirStart + 8 + 32 * bspx.size(), 0);
        std::memcpy(out.data() + dirStart, "BSPX", 4);
        putU32(out, dirStart + 4, uint32_t(bspx.size()));
        for (size_t e = 0; e < bspx.size(); ++e) {
            const size_t entry = dirStart + 8 + 32 * e;
            std::memcpy(out.data() + entry, bspx[e].name.data(), std::min<size_t>(24, bspx[e].name.size()));
            out.resize((out.size() + 3) & ~size_t(3), 0);
            putU32(out, entry + 24, uint32_t(out.size()));
            putU32(out, entry + 28, uint32_t(bspx[e].data.size()));
            out.insert(out.end(), bspx[e].data.begin(), bspx[e].data.end());
        }
    }
    return out;
}

std::vector<uint8_t> worldModelLump(const float mins[3], const float maxs[3]) {
    std::vector<uint8_t> lump;
    for (int i = 0; i < 3; ++i) appendF32(lump, mins[i]);
    for (int i = 0; i < 3; ++i) appendF32(lump, maxs[i]);
    lump.resize(40, 0);
    return lump;
}

}  // namespace q3::sh::test
