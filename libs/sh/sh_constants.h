// The one table of L2 SH constants: basis normalisations, the polynomial of each coefficient and
// the per-band convolution factors. The C++ evaluators and the GLSL generator both read it, so
// the two cannot drift apart. Real orthonormal basis in BSP axes (X east, Y north, Z up).
#pragma once

namespace q3::sh {

constexpr int kCoeffCount = 9;
constexpr int kBandCount = 3;
constexpr double kPi = 3.14159265358979323846;

// The direction polynomial that multiplies a coefficient's normalisation constant.
enum class BasisPolynomial { One, Y, Z, X, XY, YZ, ThreeZZMinusOne, XZ, XXMinusYY };

struct BasisTerm {
    int band;               // l
    int order;              // m
    double constant;        // normalisation
    BasisPolynomial poly;   // function of the unit direction (x, y, z)
};

// Y_i(x,y,z) = constant * poly(x,y,z); i = l*(l+1) + m.
constexpr BasisTerm kBasis[kCoeffCount] = {
    {0, 0, 0.282094791773878, BasisPolynomial::One},                // 1 / (2 sqrt(pi))
    {1, -1, 0.488602511902920, BasisPolynomial::Y},                 // sqrt(3) / (2 sqrt(pi))
    {1, 0, 0.488602511902920, BasisPolynomial::Z},
    {1, 1, 0.488602511902920, BasisPolynomial::X},
    {2, -2, 1.092548430592079, BasisPolynomial::XY},                // sqrt(15) / (2 sqrt(pi))
    {2, -1, 1.092548430592079, BasisPolynomial::YZ},
    {2, 0, 0.315391565252520, BasisPolynomial::ThreeZZMinusOne},   // sqrt(5) / (4 sqrt(pi))
    {2, 1, 1.092548430592079, BasisPolynomial::XZ},
    {2, 2, 0.546274215296040, BasisPolynomial::XXMinusYY},         // sqrt(15) / (4 sqrt(pi))
};

// Funk-Hecke factors of the clamped cosine max(0, n.l): turns radiance into irradiance.
constexpr double kClampedCosine[kBandCount] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0};
// Funk-Hecke factors of the hemisphere step (n.l > 0 ? 1 : 0), used by the controlled model.
constexpr double kHemisphereStep[kBandCount] = {2.0 * kPi, kPi, 0.0};
// Coefficient 0 value that evaluates to 1 everywhere: 1 / Y_0 = 2 sqrt(pi).
constexpr double kUniformToCoeff0 = 3.54490770181103205460;  // 2 * sqrt(pi)

// The polynomial as written in C-like shading languages over variables x, y, z.
constexpr const char* polynomialSource(BasisPolynomial poly) {
    switch (poly) {
        case BasisPolynomial::One: return "1.0";
        case BasisPolynomial::Y: return "y";
        case BasisPolynomial::Z: return "z";
        case BasisPolynomial::X: return "x";
        case BasisPolynomial::XY: return "x * y";
        case BasisPolynomial::YZ: return "y * z";
        case BasisPolynomial::ThreeZZMinusOne: return "3.0 * z * z - 1.0";
        case BasisPolynomial::XZ: return "x * z";
        case BasisPolynomial::XXMinusYY: return "x * x - y * y";
    }
    return "0.0";
}

template <typename T>
constexpr T polynomialValue(BasisPolynomial poly, T x, T y, T z) {
    switch (poly) {
        case BasisPolynomial::One: return T(1);
        case BasisPolynomial::Y: return y;
        case BasisPolynomial::Z: return z;
        case BasisPolynomial::X: return x;
        case BasisPolynomial::XY: return x * y;
        case BasisPolynomial::YZ: return y * z;
        case BasisPolynomial::ThreeZZMinusOne: return T(3) * z * z - T(1);
        case BasisPolynomial::XZ: return x * z;
        case BasisPolynomial::XXMinusYY: return x * x - y * y;
    }
    return T(0);
}

// Evaluates all nine basis functions for a unit direction; T is float (engines) or double.
template <typename T>
constexpr void evalBasisInto(T x, T y, T z, T out[kCoeffCount]) {
    for (int i = 0; i < kCoeffCount; ++i)
        out[i] = T(kBasis[i].constant) * polynomialValue(kBasis[i].poly, x, y, z);
}

}  // namespace q3::sh
