// Codec and validation of the WORLDLIGHTS lump (docs/world-lights-format.md).
#include "world_lights.h"

#include <cmath>
#include <cstdio>

#include "le_bytes.h"

namespace q3::sh {
namespace {

constexpr char kMagic[4] = {'W', 'L', 'I', 'T'};
// Coordinates and distances beyond this are not map data (q3map2 maps end at +-65536).
constexpr float kAbsurdDistance = 1.0e6f;
constexpr float kUnitTolerance = 1.0e-3f;

std::string format(const char* fmt, double a, double b = 0) {
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, fmt, a, b);
    return buffer;
}

bool allFinite(const float* v, int n) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

bool isUnit(const std::array<float, 3>& v) {
    const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::fabs(len - 1.0f) <= kUnitTolerance;
}

std::string checkFalloff(const WorldLight& l) {
    const auto& c = l.falloffConstants;
    switch (l.falloff) {
        case WorldLightFalloff::InverseSquare:
        case WorldLightFalloff::Linear:
            if (!(c[0] > 0) || c[0] > kAbsurdDistance) return format("minimum distance %g is not in (0, 1e6]", c[0]);
            if (c[1] < 0 || c[1] > kAbsurdDistance) return format("extra distance %g is not in [0, 1e6]", c[1]);
            if (c[2] < 0) return format("cutoff %g is negative", c[2]);
            if (l.falloff == WorldLightFalloff::Linear ? c[3] < 0 : c[3] != 0)
                return format("falloff constant 3 is %g (the fade rate of linear lights, else 0)", c[3]);
            return {};
        case WorldLightFalloff::Controlled:
            if (c[0] < 0 || c[1] < c[0] || c[1] > kAbsurdDistance)
                return format("controlled falloff start %g and end %g are not 0 <= start <= end <= 1e6", c[0], c[1]);
            if (c[2] < 0 || c[2] > 1) return format("controlled falloff curvature %g is not in [0, 1]", c[2]);
            if (c[3] != 0) return format("falloff constant 3 is %g, not 0", c[3]);
            return {};
        case WorldLightFalloff::Parallel:
            for (float v : c)
                if (v != 0) return format("parallel falloff constant %g is not 0", v);
            return {};
    }
    return format("unknown falloff model %g", double(uint32_t(l.falloff)));
}

std::string checkCone(const WorldLight& l) {
    const auto& c = l.cone;
    if (l.type != WorldLightType::Spot) {
        for (float v : c)
            if (v != 0) return format("cone constant %g of a light that is not a spot is not 0", v);
        return {};
    }
    if (l.falloff == WorldLightFalloff::Controlled) {
        if (c[0] < 0 || c[1] < c[0] || c[1] > 180)
            return format("spot half angles %g and %g are not 0 <= inner <= outer <= 180", c[0], c[1]);
        if (c[2] < 0 || c[2] > 1) return format("spherical ambient %g is not in [0, 1]", c[2]);
    } else {
        if (!(c[0] > 0) || c[0] > kAbsurdDistance) return format("spot radius per unit %g is not in (0, 1e6]", c[0]);
        if (c[1] < 0 || c[1] > kAbsurdDistance) return format("spot fade width %g is not in [0, 1e6]", c[1]);
        if (c[2] != 0) return format("cone constant 2 is %g, not 0", c[2]);
    }
    if (c[3] != 0) return format("cone constant 3 is %g, not 0", c[3]);
    return {};
}

void writeVec(uint8_t* p, const float* v, int n) {
    for (int i = 0; i < n; ++i) le::writeF32(p + 4 * i, v[i]);
}
void readVec(const uint8_t* p, float* v, int n) {
    for (int i = 0; i < n; ++i) v[i] = le::readF32(p + 4 * i);
}

// Record fields; the raw type and model are checked before they become enumerators.
WorldLight readRecord(const uint8_t* p) {
    WorldLight l;
    l.type = WorldLightType(le::readU32(p + 0));
    l.falloff = WorldLightFalloff(le::readU32(p + 4));
    l.flags = le::readU32(p + 8);
    l.style = le::readI32(p + 12);
    l.cluster = le::readI32(p + 16);
    readVec(p + 20, l.origin.data(), 3);
    readVec(p + 32, l.intensity.data(), 3);
    readVec(p + 44, l.direction.data(), 3);
    readVec(p + 56, l.falloffConstants.data(), 4);
    readVec(p + 72, l.cone.data(), 4);
    l.incidenceWeight = le::readF32(p + 88);
    l.radius = le::readF32(p + 92);
    return l;
}

}  // namespace

std::string checkWorldLight(const WorldLight& l) {
    const uint32_t type = uint32_t(l.type);
    const uint32_t model = uint32_t(l.falloff);
    if (type > uint32_t(WorldLightType::Sun)) return format("unknown type %.0f", type);
    if (model > uint32_t(WorldLightFalloff::Parallel)) return format("unknown falloff model %.0f", model);
    const bool sun = l.type == WorldLightType::Sun;
    if (sun != (l.falloff == WorldLightFalloff::Parallel))
        return sun ? "a sun with a falloff model other than parallel" : "a parallel falloff on a light that is not a sun";
    if (l.flags & ~kWorldLightKnownFlags) return format("unknown flag bits %.0f", double(l.flags & ~kWorldLightKnownFlags));
    if (l.style < 0 || l.style > 255) return format("style %.0f is not in 0..255", l.style);
    if (l.cluster < -1) return format("cluster %.0f is below -1", l.cluster);
    if (sun && l.cluster != -1) return format("a sun in cluster %.0f (suns have -1)", l.cluster);
    const float* fields[] = {l.origin.data(), l.intensity.data(), l.direction.data(), l.falloffConstants.data(),
                             l.cone.data()};
    const int counts[] = {3, 3, 3, 4, 4};
    for (int i = 0; i < 5; ++i)
        if (!allFinite(fields[i], counts[i])) return "a value that is not a finite number";
    if (!std::isfinite(l.incidenceWeight) || !std::isfinite(l.radius)) return "a value that is not a finite number";
    for (float v : l.origin)
        if (std::fabs(v) > kAbsurdDistance) return format("origin coordinate %g is beyond 1e6", v);
    if ((sun || l.type == WorldLightType::Spot) && !isUnit(l.direction)) return "direction is not a unit vector";
    if (l.incidenceWeight < 0 || l.incidenceWeight > 1) return format("incidence weight %g is not in [0, 1]", l.incidenceWeight);
    if (l.radius < 0 || l.radius > kAbsurdDistance) return format("radius %g is not in [0, 1e6]", l.radius);
    if (sun && l.radius != 0) return format("a sun with radius %g (suns have 0)", l.radius);
    if (std::string e = checkFalloff(l); !e.empty()) return e;
    return checkCone(l);
}

std::string checkWorldLightsLump(const uint8_t* data, size_t size) {
    const std::string name = std::string(kWorldLightsLumpName) + ": ";
    if (data == nullptr && size != 0) return name + "no data";
    if (size < kWorldLightsHeaderBytes)
        return name + format("%.0f bytes, shorter than the %.0f-byte header", double(size), double(kWorldLightsHeaderBytes));
    for (int i = 0; i < 4; ++i)
        if (data[i] != uint8_t(kMagic[i])) return name + "magic is not WLIT";
    const uint32_t version = le::readU32(data + 4);
    if (version != kWorldLightsVersion) return name + format("unsupported version %.0f (expected %.0f)", version, kWorldLightsVersion);
    const uint32_t count = le::readU32(data + 8);
    const uint32_t recordBytes = le::readU32(data + 12);
    if (recordBytes != kWorldLightRecordBytes)
        return name + format("record size %.0f, expected %.0f", recordBytes, double(kWorldLightRecordBytes));
    const uint64_t expected = kWorldLightsHeaderBytes + uint64_t(count) * kWorldLightRecordBytes;
    if (expected != size)
        return name + format("%.0f lights need %.0f bytes", count, double(expected)) +
               format(", the lump has %.0f", double(size));
    for (uint32_t i = 0; i < count; ++i) {
        const WorldLight l = readRecord(data + kWorldLightsHeaderBytes + size_t(i) * kWorldLightRecordBytes);
        if (std::string e = checkWorldLight(l); !e.empty()) return name + format("light %.0f: ", i) + e;
    }
    return {};
}

bool decodeWorldLights(const uint8_t* data, size_t size, std::vector<WorldLight>& out, std::string& error) {
    error = checkWorldLightsLump(data, size);
    if (!error.empty()) return false;
    const uint32_t count = le::readU32(data + 8);
    out.clear();
    out.reserve(count);
    for (uint32_t i = 0; i < count; ++i)
        out.push_back(readRecord(data + kWorldLightsHeaderBytes + size_t(i) * kWorldLightRecordBytes));
    return true;
}

std::vector<uint8_t> encodeWorldLights(std::span<const WorldLight> lights) {
    std::vector<uint8_t> bytes(kWorldLightsHeaderBytes + lights.size() * kWorldLightRecordBytes);
    uint8_t* p = bytes.data();
    for (int i = 0; i < 4; ++i) p[i] = uint8_t(kMagic[i]);
    le::writeU32(p + 4, kWorldLightsVersion);
    le::writeU32(p + 8, uint32_t(lights.size()));
    le::writeU32(p + 12, uint32_t(kWorldLightRecordBytes));
    p += kWorldLightsHeaderBytes;
    for (const WorldLight& l : lights) {
        le::writeU32(p + 0, uint32_t(l.type));
        le::writeU32(p + 4, uint32_t(l.falloff));
        le::writeU32(p + 8, l.flags);
        le::writeI32(p + 12, l.style);
        le::writeI32(p + 16, l.cluster);
        writeVec(p + 20, l.origin.data(), 3);
        writeVec(p + 32, l.intensity.data(), 3);
        writeVec(p + 44, l.direction.data(), 3);
        writeVec(p + 56, l.falloffConstants.data(), 4);
        writeVec(p + 72, l.cone.data(), 4);
        le::writeF32(p + 88, l.incidenceWeight);
        le::writeF32(p + 92, l.radius);
        p += kWorldLightRecordBytes;
    }
    return bytes;
}

}  // namespace q3::sh
