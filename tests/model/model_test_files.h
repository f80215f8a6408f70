// Small model files written by the tests themselves, for the model library and misc_model tests.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace q3::model::test {

// An MD3 image with one surface "body" (shader "models/test/skin.tga") of the given vertices (in
// 1/64 units, normal +Z), triangles and texture coordinates.
std::vector<uint8_t> md3Image(const std::vector<std::array<int16_t, 3>>& verts,
                              const std::vector<std::array<int32_t, 3>>& tris,
                              const std::vector<std::array<float, 2>>& st);

}  // namespace q3::model::test
