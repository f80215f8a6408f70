#include "model_transform.h"

#include <cmath>

namespace q3::bspstage {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The transpose of the inverse of the 3x3 part; the determinant's parts are float products, the
// scaling is done in doubles.
void normalMatrix(const float (&s)[16], float (&out)[16]) {
    const double det = s[0] * (s[5] * s[10] - s[9] * s[6]) - s[1] * (s[4] * s[10] - s[8] * s[6]) +
                       s[2] * (s[4] * s[9] - s[8] * s[5]);
    const double inv = 1.0 / det;
    float r[9];
    r[0] = float((s[5] * s[10] - s[6] * s[9]) * inv);
    r[1] = float(-(s[1] * s[10] - s[2] * s[9]) * inv);
    r[2] = float((s[1] * s[6] - s[2] * s[5]) * inv);
    r[3] = float(-(s[4] * s[10] - s[6] * s[8]) * inv);
    r[4] = float((s[0] * s[10] - s[2] * s[8]) * inv);
    r[5] = float(-(s[0] * s[6] - s[2] * s[4]) * inv);
    r[6] = float((s[4] * s[9] - s[5] * s[8]) * inv);
    r[7] = float(-(s[0] * s[9] - s[1] * s[8]) * inv);
    r[8] = float((s[0] * s[5] - s[1] * s[4]) * inv);
    for (float& v : out) v = 0;
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) out[col * 4 + row] = r[row * 3 + col];  // transposed
    out[15] = 1;
}

}  // namespace

ModelTransform::ModelTransform() : m_{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, n_{} {
    normalMatrix(m_, n_);
}

ModelTransform ModelTransform::place(const Vec3& origin, float pitch, float yaw, float roll, const Vec3& scale) {
    // Angles become radians stored as floats before their sines and cosines are taken in doubles.
    const float x = float(double(roll) * kPi / 180.0), y = float(double(pitch) * kPi / 180.0),
                z = float(double(yaw) * kPi / 180.0);
    const double cx = std::cos(x), sx = std::sin(x), cy = std::cos(y), sy = std::sin(y), cz = std::cos(z), sz = std::sin(z);
    const float rotation[9] = {float(cy * cz),           float(cy * sz),           float(-sy),
                               float(sx * sy * cz + cx * -sz), float(sx * sy * sz + cx * cz), float(sx * cy),
                               float(cx * sy * cz + sx * sz),  float(cx * sy * sz + -sx * cz), float(cx * cy)};
    ModelTransform t;
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row) t.m_[col * 4 + row] = rotation[col * 3 + row] * scale[col];
    for (int row = 0; row < 3; ++row) t.m_[12 + row] = origin[row];
    normalMatrix(t.m_, t.n_);
    return t;
}

ModelTransform ModelTransform::skybox(const Vec3& origin, float pitch, float yaw, float roll, const Vec3& scale) {
    ModelTransform t = place({0, 0, 0}, pitch, yaw, roll, scale);
    // The translation to -origin comes last: it passes through the turn and scale, in floats.
    for (int row = 0; row < 3; ++row)
        t.m_[12 + row] = -origin.x * t.m_[row] + -origin.y * t.m_[4 + row] + -origin.z * t.m_[8 + row] + t.m_[12 + row];
    return t;
}

Vec3 ModelTransform::point(const Vec3& p) const {
    return {p.x * m_[0] + p.y * m_[4] + p.z * m_[8] + m_[12], p.x * m_[1] + p.y * m_[5] + p.z * m_[9] + m_[13],
            p.x * m_[2] + p.y * m_[6] + p.z * m_[10] + m_[14]};
}

DVec3 ModelTransform::pointInDoubles(const Vec3& p) const {
    const double x = p.x, y = p.y, z = p.z;
    return {m_[0] * x + m_[4] * y + m_[8] * z + m_[12], m_[1] * x + m_[5] * y + m_[9] * z + m_[13],
            m_[2] * x + m_[6] * y + m_[10] * z + m_[14]};
}

Vec3 ModelTransform::normal(const Vec3& d) const {
    return {d.x * n_[0] + d.y * n_[4] + d.z * n_[8], d.x * n_[1] + d.y * n_[5] + d.z * n_[9],
            d.x * n_[2] + d.y * n_[6] + d.z * n_[10]};
}

bool ModelTransform::leftHanded() const {
    const Vec3 x{m_[0], m_[1], m_[2]}, y{m_[4], m_[5], m_[6]}, z{m_[8], m_[9], m_[10]};
    return dot(cross(x, y), z) < 0;
}

}  // namespace q3::bspstage
