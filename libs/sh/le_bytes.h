// Little-endian 32-bit fields of the lump codecs, assembled byte by byte so the file formats do not
// depend on the host's byte order.
#pragma once

#include <cstdint>
#include <cstring>

namespace q3::sh::le {

inline uint32_t readU32(const uint8_t* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
inline int32_t readI32(const uint8_t* p) {
    const uint32_t u = readU32(p);
    int32_t v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}
inline float readF32(const uint8_t* p) {
    const uint32_t u = readU32(p);
    float v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}
inline void writeU32(uint8_t* p, uint32_t u) {
    p[0] = uint8_t(u);
    p[1] = uint8_t(u >> 8);
    p[2] = uint8_t(u >> 16);
    p[3] = uint8_t(u >> 24);
}
inline void writeI32(uint8_t* p, int32_t v) {
    uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    writeU32(p, u);
}
inline void writeF32(uint8_t* p, float v) {
    uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    writeU32(p, u);
}

}  // namespace q3::sh::le
