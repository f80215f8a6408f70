// The WORLDLIGHTS codec: round trip, every malformed input rejected with one line naming the lump,
// and the evaluation formula of docs/world-lights-format.md on values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "sh_test_support.h"
#include "world_lights.h"
#include "world_lights_samples.h"

namespace q3::sh {
namespace {

using test::putF32;
using test::putU32;
using test::sampleWorldLights;

size_t recordAt(size_t index) { return kWorldLightsHeaderBytes + index * kWorldLightRecordBytes; }

TEST(WorldLightsCodec, RoundTripKeepsEveryField) {
    const std::vector<WorldLight> lights = sampleWorldLights();
    const std::vector<uint8_t> bytes = encodeWorldLights(lights);
    ASSERT_EQ(bytes.size(), 16u + 96u * lights.size());
    EXPECT_EQ(std::memcmp(bytes.data(), "WLIT", 4), 0);
    EXPECT_EQ(bytes[4], 1);   // version
    EXPECT_EQ(bytes[8], lights.size());
    EXPECT_EQ(bytes[12], 96);
    std::vector<WorldLight> decoded;
    std::string error;
    ASSERT_TRUE(decodeWorldLights(bytes.data(), bytes.size(), decoded, error)) << error;
    ASSERT_EQ(decoded.size(), lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        EXPECT_EQ(decoded[i].type, lights[i].type);
        EXPECT_EQ(decoded[i].falloff, lights[i].falloff);
        EXPECT_EQ(decoded[i].flags, lights[i].flags);
        EXPECT_EQ(decoded[i].style, lights[i].style);
        EXPECT_EQ(decoded[i].cluster, lights[i].cluster);
        EXPECT_EQ(decoded[i].origin, lights[i].origin);
        EXPECT_EQ(decoded[i].intensity, lights[i].intensity);
        EXPECT_EQ(decoded[i].direction, lights[i].direction);
        EXPECT_EQ(decoded[i].falloffConstants, lights[i].falloffConstants);
        EXPECT_EQ(decoded[i].cone, lights[i].cone);
        EXPECT_EQ(decoded[i].incidenceWeight, lights[i].incidenceWeight);
        EXPECT_EQ(decoded[i].radius, lights[i].radius);
    }
    EXPECT_EQ(encodeWorldLights(decoded), bytes);
    // A field's bytes sit where the document says: the spot's cone constant 0 at record offset 72.
    float k;
    std::memcpy(&k, bytes.data() + recordAt(2) + 72, 4);
    EXPECT_EQ(k, 0.4f);
    const std::vector<uint8_t> empty = encodeWorldLights({});
    EXPECT_EQ(empty.size(), 16u);
    EXPECT_TRUE(decodeWorldLights(empty.data(), empty.size(), decoded, error)) << error;
    EXPECT_TRUE(decoded.empty());
}

struct Malformed {
    const char* name;
    std::function<void(std::vector<uint8_t>&)> edit;
    const char* expected;  // part of the message
};

TEST(WorldLightsCodec, MalformedLumpsGiveOneLineNamingTheProblem) {
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const size_t point = recordAt(0), spot = recordAt(2), controlled = recordAt(3), sun = recordAt(4);
    const std::vector<Malformed> cases = {
        {"short", [](auto& b) { b.resize(10); }, "shorter than the 16-byte header"},
        {"magic", [](auto& b) { b[0] = 'X'; }, "magic is not WLIT"},
        {"version", [](auto& b) { putU32(b, 4, 2); }, "unsupported version 2"},
        {"record size", [](auto& b) { putU32(b, 12, 80); }, "record size 80"},
        {"count too large", [](auto& b) { putU32(b, 8, 6); }, "6 lights need 592 bytes, the lump has 496"},
        {"huge count", [](auto& b) { putU32(b, 8, 0xffffffffu); }, "4294967295 lights need"},
        {"truncated", [](auto& b) { b.pop_back(); }, "the lump has 495"},
        {"trailing bytes", [](auto& b) { b.push_back(0); }, "the lump has 497"},
        {"type", [&](auto& b) { putU32(b, point, 7); }, "light 0: unknown type 7"},
        {"falloff", [&](auto& b) { putU32(b, point + 4, 9); }, "light 0: unknown falloff model 9"},
        {"sun falloff", [&](auto& b) { putU32(b, sun + 4, 0); }, "light 4: a sun with a falloff model other"},
        {"parallel point", [&](auto& b) { putU32(b, point + 4, 3); }, "a parallel falloff on a light that is not a sun"},
        {"flags", [&](auto& b) { putU32(b, point + 8, 6); }, "unknown flag bits 6"},
        {"style", [&](auto& b) { putU32(b, point + 12, 300); }, "style 300 is not in 0..255"},
        {"cluster", [&](auto& b) { putU32(b, point + 16, uint32_t(-2)); }, "cluster -2 is below -1"},
        {"sun cluster", [&](auto& b) { putU32(b, sun + 16, 4); }, "a sun in cluster 4"},
        {"NaN intensity", [&](auto& b) { putF32(b, point + 36, kNaN); }, "not a finite number"},
        {"inf origin", [&](auto& b) { putF32(b, point + 20, kInf); }, "not a finite number"},
        {"NaN radius", [&](auto& b) { putF32(b, point + 92, kNaN); }, "not a finite number"},
        {"far origin", [&](auto& b) { putF32(b, point + 24, -2e6f); }, "origin coordinate -2e+06 is beyond 1e6"},
        {"direction", [&](auto& b) { putF32(b, spot + 52, -0.5f); }, "direction is not a unit vector"},
        {"weight", [&](auto& b) { putF32(b, point + 88, 1.5f); }, "incidence weight 1.5"},
        {"radius", [&](auto& b) { putF32(b, point + 92, -1); }, "radius -1 is not in"},
        {"sun radius", [&](auto& b) { putF32(b, sun + 92, 10); }, "a sun with radius 10"},
        {"min distance", [&](auto& b) { putF32(b, point + 56, 0); }, "minimum distance 0"},
        {"extra distance", [&](auto& b) { putF32(b, point + 60, -3); }, "extra distance -3"},
        {"cutoff", [&](auto& b) { putF32(b, point + 64, -1); }, "cutoff -1 is negative"},
        {"rate on inverse square", [&](auto& b) { putF32(b, point + 68, 2); }, "falloff constant 3 is 2"},
        {"end before start", [&](auto& b) { putF32(b, controlled + 60, 10); }, "start 32 and end 10"},
        {"curvature", [&](auto& b) { putF32(b, controlled + 64, 2); }, "curvature 2 is not in [0, 1]"},
        {"half angle", [&](auto& b) { putF32(b, controlled + 76, 200); }, "spot half angles 22.5 and 200"},
        {"spherical ambient", [&](auto& b) { putF32(b, controlled + 80, -0.5f); }, "spherical ambient -0.5"},
        {"spot slope", [&](auto& b) { putF32(b, spot + 72, 0); }, "spot radius per unit 0"},
        {"cone on a point", [&](auto& b) { putF32(b, point + 72, 1); }, "not a spot is not 0"},
        {"parallel constant", [&](auto& b) { putF32(b, sun + 56, 1); }, "parallel falloff constant 1"},
    };
    const std::vector<uint8_t> good = encodeWorldLights(sampleWorldLights());
    ASSERT_EQ(checkWorldLightsLump(good.data(), good.size()), "");
    for (const Malformed& c : cases) {
        std::vector<uint8_t> bytes = good;
        c.edit(bytes);
        const std::string error = checkWorldLightsLump(bytes.data(), bytes.size());
        EXPECT_TRUE(error.starts_with("WORLDLIGHTS: ")) << c.name << ": " << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.name << ": " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << c.name;
        std::vector<WorldLight> decoded;
        std::string decodeError;
        EXPECT_FALSE(decodeWorldLights(bytes.data(), bytes.size(), decoded, decodeError)) << c.name;
        EXPECT_EQ(decodeError, error) << c.name;
    }
    EXPECT_NE(checkWorldLightsLump(nullptr, 4).find("no data"), std::string::npos);
    EXPECT_NE(checkWorldLightsLump(nullptr, 0).find("shorter than"), std::string::npos);
}

std::array<float, 3> at(float x, float y, float z) { return {x, y, z}; }

TEST(WorldLightsEvaluate, InverseSquareAndLinearPointLights) {
    WorldLight l = sampleWorldLights()[0];  // origin (128.5, -64.25, 96), cutoff 1e-5, radius 700
    const auto below = at(128.5f, -64.25f, -4);  // 100 units under it
    const auto e = evaluateWorldLight(l, below, at(0, 0, 1));
    EXPECT_FLOAT_EQ(e[0], 2.5f / 10000);
    EXPECT_FLOAT_EQ(e[1], 1.25f / 10000);
    // Lambert: a normal at 60 degrees from the light halves it; facing away gives nothing.
    EXPECT_NEAR(evaluateWorldLight(l, below, at(std::sqrt(3.f) / 2, 0, 0.5f))[0], 2.5f / 20000, 1e-8);
    EXPECT_EQ(evaluateWorldLight(l, below, at(0, 0, -1))[0], 0);
    EXPECT_FLOAT_EQ(worldLightArriving(l, below)[0], 2.5f / 10000);
    // Within the 16-unit clamp the value stays at 1/256.
    EXPECT_FLOAT_EQ(worldLightArriving(l, at(128.5f, -64.25f, 90))[0], 2.5f / 256);
    // 1/D^2 <= cutoff 1e-5 from D = sqrt(1e5) = 316.2 on: nothing.
    EXPECT_GT(worldLightArriving(l, at(128.5f, -64.25f, 96 - 316))[0], 0);
    EXPECT_EQ(worldLightArriving(l, at(128.5f, -64.25f, 96 - 317))[0], 0);
    l.falloffConstants[2] = 0;
    EXPECT_GT(worldLightArriving(l, at(128.5f, -64.25f, 96 - 317))[0], 0);
    EXPECT_EQ(worldLightArriving(l, at(128.5f, -64.25f, 96 - 701))[0], 0);  // beyond the radius

    const WorldLight linear = sampleWorldLights()[1];  // extra 8, rate 0.0025
    const float d = std::sqrt(100.f * 100.f + 64.f);
    EXPECT_NEAR(worldLightArriving(linear, below)[0], 2.5f * (1 - d * 0.0025f), 1e-6);
    EXPECT_EQ(worldLightArriving(linear, at(128.5f, -64.25f, 96 - 401))[0], 0);  // 1 - D * rate < 0
}

TEST(WorldLightsEvaluate, SpotConesAndSuns) {
    const WorldLight spot = sampleWorldLights()[2];  // at (0,0,200) pointing down, k 0.4, fade 32
    // 100 units down the axis the cone's radius is 40: inside at 5, fading at 20, dark at 41.
    EXPECT_NEAR(worldLightArriving(spot, at(5, 0, 100))[0], 40.f / (100 * 100 + 25), 1e-6 * 40.f / 10025);
    const float r20 = std::sqrt(100.f * 100.f + 400.f);
    EXPECT_NEAR(worldLightArriving(spot, at(20, 0, 100))[0], 40.f / (r20 * r20) * (40 - 20) / 32.f, 1e-7);
    EXPECT_EQ(worldLightArriving(spot, at(41, 0, 100))[0], 0);
    EXPECT_EQ(worldLightArriving(spot, at(0, 0, 300))[0], 0);  // behind

    const WorldLight controlled = sampleWorldLights()[3];  // inner 22.5, outer 30, ambient 0.1, w 0.5
    const auto origin = controlled.origin;
    const auto onAxis = at(origin[0] + 0.6f * 32, origin[1] + 0.8f * 32, origin[2]);  // at falloff start
    const auto facing = at(-0.6f, -0.8f, 0);
    EXPECT_NEAR(evaluateWorldLight(controlled, onAxis, facing)[0], 0.8f, 1e-5);
    // A normal at 90 degrees: incidence (1 - w) = 0.5 only where n.l > 0, so 0 exactly side-on.
    EXPECT_EQ(evaluateWorldLight(controlled, onAxis, at(0, 0, 1))[0], 0);
    // Outside the outer cone: only the spherical ambient fraction.
    const auto sideways = at(origin[0] - 0.8f * 32, origin[1] + 0.6f * 32, origin[2]);
    EXPECT_NEAR(worldLightArriving(controlled, sideways)[0], 0.8f * 0.1f, 1e-6);
    EXPECT_EQ(worldLightArriving(controlled, at(origin[0] + 0.6f * 401, origin[1] + 0.8f * 401, origin[2]))[0], 0);

    const WorldLight sun = sampleWorldLights()[4];  // towards (0, 0.6, 0.8)
    EXPECT_FLOAT_EQ(evaluateWorldLight(sun, at(1e5f, 0, 0), at(0, 0, 1))[0], 0.9f * 0.8f);
    EXPECT_EQ(evaluateWorldLight(sun, at(0, 0, 0), at(0, -0.6f, -0.8f))[0], 0);
}

}  // namespace
}  // namespace q3::sh
