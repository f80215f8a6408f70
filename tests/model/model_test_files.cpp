#include "model_test_files.h"

#include <cstring>

namespace q3::model::test {

std::vector<uint8_t> md3Image(const std::vector<std::array<int16_t, 3>>& verts, const std::vector<std::array<int32_t, 3>>& tris,
                              const std::vector<std::array<float, 2>>& st) {
    std::vector<uint8_t> out(108, 0);
    auto put = [&](size_t at, const void* data, size_t size) {
        if (out.size() < at + size) out.resize(at + size);
        std::memcpy(out.data() + at, data, size);
    };
    auto putInt = [&](size_t at, int32_t v) { put(at, &v, 4); };
    put(0, "IDP3", 4);
    putInt(4, 15);
    putInt(76, 1);    // frames
    putInt(84, 1);    // surfaces
    putInt(100, 108); // surfaces offset
    const size_t s = 108;
    const int32_t headerSize = 108, shadersAt = headerSize, trisAt = shadersAt + 68;
    const int32_t stAt = trisAt + int32_t(tris.size()) * 12, xyzAt = stAt + int32_t(verts.size()) * 8;
    const int32_t end = xyzAt + int32_t(verts.size()) * 8;
    put(s, "IDP3", 4);
    put(s + 4, "body", 4);
    putInt(s + 72, 1);
    putInt(s + 76, 1);
    putInt(s + 80, int32_t(verts.size()));
    putInt(s + 84, int32_t(tris.size()));
    putInt(s + 88, trisAt);
    putInt(s + 92, shadersAt);
    putInt(s + 96, stAt);
    putInt(s + 100, xyzAt);
    putInt(s + 104, end);
    put(s + size_t(shadersAt), "models/test/skin.tga", 20);
    out.resize(s + size_t(end), 0);
    for (size_t i = 0; i < tris.size(); ++i) put(s + size_t(trisAt) + i * 12, tris[i].data(), 12);
    for (size_t i = 0; i < verts.size(); ++i) {
        put(s + size_t(stAt) + i * 8, st[i].data(), 8);
        put(s + size_t(xyzAt) + i * 8, verts[i].data(), 6);  // normal 0: lat 0, lng 0 = +Z
    }
    return out;
}

}  // namespace q3::model::test
