// Helpers of the SH tests: sphere quadratures, seeded random directions, BSP images built by hand.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sh.h"

namespace q3::sh::test {

struct WeightedDir {
    Vec3d dir;
    double weight;
};

// Gauss-Legendre nodes and weights on [a, b].
void gaussLegendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

// Product rule over the cap of directions whose cosine to `pole` lies in [cosMin, cosMax]:
// Gauss-Legendre in the cosine, uniform in azimuth. Exact for polynomials of degree
// < min(2*cosNodes, azimuthNodes) in the direction's components.
std::vector<WeightedDir> capQuadrature(Vec3d pole, double cosMin, double cosMax, int cosNodes, int azimuthNodes);
std::vector<WeightedDir> sphereQuadrature(int cosNodes, int azimuthNodes);

// Nearly uniform deterministic points on the sphere (Fibonacci lattice).
std::vector<Vec3d> fibonacciSphere(int count);

Vec3d randomDirection(std::mt19937& rng);

double dot(Vec3d a, Vec3d b);

// A little-endian BSP image: ident IBSP, `version`, `lumpCount` directory entries, lumps laid out
// 4-byte aligned in index order, then an optional BSPX trailer.
struct BspxEntry {
    std::string name;
    std::vector<uint8_t> data;
};
std::vector<uint8_t> buildBsp(int version, int lumpCount, const std::vector<std::vector<uint8_t>>& lumps,
                              const std::vector<BspxEntry>& bspx = {});

void putU32(std::vector<uint8_t>& bytes, size_t at, uint32_t value);
void putF32(std::vector<uint8_t>& bytes, size_t at, float value);
void appendF32(std::vector<uint8_t>& bytes, float value);

// A model lump holding only model 0 with the given bounds.
std::vector<uint8_t> worldModelLump(const float mins[3], const float maxs[3]);

}  // namespace q3::sh::test
