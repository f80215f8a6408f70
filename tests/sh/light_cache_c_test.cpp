// The light cache's C interface: the C++ results field by field, failures as NULL plus one line,
// null-safe everywhere, and callable from a C translation unit.
#include <gtest/gtest.h>

#include <cstring>

#include "light_cache.h"
#include "light_cache_c.h"
#include "light_cache_test_bsp.h"
#include "world_lights_glsl.h"

extern "C" int q3sh_test_c_light_cache(const unsigned char* bsp, size_t size, const float position[3],
                                       unsigned* firstIndex, char* error, size_t errorSize);

namespace q3::sh {
namespace {

std::vector<uint8_t> roomWithTwoLights() {
    test::TestMap map = test::roomWithPillar();
    map.lights.push_back(test::testPointLight(200, -200, 200, 1000));
    return test::buildTestBsp(map);
}

TEST(LightCacheC, MatchesTheCppCache) {
    const std::vector<uint8_t> bsp = roomWithTwoLights();
    char error[128] = "unset";
    q3sh_lightcache* cache = q3sh_lightcache_load(bsp.data(), bsp.size(), error, sizeof error);
    ASSERT_NE(cache, nullptr) << error;
    EXPECT_STREQ(error, "");
    EXPECT_EQ(q3sh_lightcache_light_count(cache), 2u);

    LightCache cpp;
    ASSERT_EQ(cpp.loadFromBsp(bsp.data(), bsp.size()), "");
    const float p[3] = {200, 200, 64};
    q3sh_lightcache_result r;
    q3sh_lightcache_query(cache, p, 1, &r);
    const LightCacheResult expected = cpp.query(p, 1);
    EXPECT_EQ(std::memcmp(r.coeffs, expected.probe.coeffs, sizeof r.coeffs), 0);
    ASSERT_EQ(r.localCount, 1);
    EXPECT_EQ(r.local[0].index, 0u);
    EXPECT_EQ(r.local[0].arriving[0], expected.local[0].arriving[0]);
    const WorldLightGpu gpu = packWorldLightGpu(cpp.lights()[0]);
    EXPECT_EQ(std::memcmp(r.local[0].gpu, &gpu, sizeof gpu), 0);
    EXPECT_EQ(r.local[0].gpu[0], -200.f);  // origin x
    EXPECT_EQ(r.cluster, 0);
    EXPECT_EQ(r.projectedCount, 1u);
    EXPECT_EQ(r.occludedCount, 0u);

    const float normal[3] = {-1, 0, 0};
    float rgb[3];
    q3sh_lightcache_eval_light(cache, 1, p, normal, rgb);
    const auto e = evaluateWorldLight(cpp.lights()[1], {200, 200, 64}, {-1, 0, 0});
    EXPECT_EQ(rgb[0], e[0]);
    q3sh_lightcache_eval_light(cache, 2, p, normal, rgb);  // out of range
    EXPECT_EQ(rgb[0], 0);
    q3sh_lightcache_free(cache);
}

TEST(LightCacheC, FailuresAndNullsAreHarmless) {
    std::vector<uint8_t> bsp = roomWithTwoLights();
    bsp.resize(200);
    char error[128];
    EXPECT_EQ(q3sh_lightcache_load(bsp.data(), bsp.size(), error, sizeof error), nullptr);
    EXPECT_NE(std::strstr(error, "lies outside the file"), nullptr) << error;
    EXPECT_EQ(std::strchr(error, '\n'), nullptr);
    EXPECT_EQ(q3sh_lightcache_load(nullptr, 0, nullptr, 0), nullptr);
    char tiny[4];
    EXPECT_EQ(q3sh_lightcache_load(nullptr, 0, tiny, sizeof tiny), nullptr);
    EXPECT_EQ(std::strlen(tiny), 3u);  // cut to fit

    q3sh_lightcache_result r;
    r.localCount = 9;
    const float p[3] = {0, 0, 0};
    q3sh_lightcache_query(nullptr, p, 4, &r);
    EXPECT_EQ(r.localCount, 0);
    EXPECT_EQ(r.cluster, -1);
    q3sh_lightcache_query(nullptr, p, 4, nullptr);
    EXPECT_EQ(q3sh_lightcache_light_count(nullptr), 0u);
    float rgb[3] = {1, 1, 1};
    q3sh_lightcache_eval_light(nullptr, 0, p, p, rgb);
    EXPECT_EQ(rgb[0], 0);
    q3sh_lightcache_eval_light(nullptr, 0, p, p, nullptr);
    q3sh_lightcache_free(nullptr);
}

TEST(LightCacheC, CallableFromC) {
    const std::vector<uint8_t> bsp = roomWithTwoLights();
    const float inView[3] = {200, 200, 64}, behind[3] = {200, 0, 64};
    unsigned first = 99;
    char error[64];
    EXPECT_EQ(q3sh_test_c_light_cache(bsp.data(), bsp.size(), inView, &first, error, sizeof error), 2);
    EXPECT_EQ(first, 0u);
    EXPECT_EQ(q3sh_test_c_light_cache(bsp.data(), bsp.size(), behind, &first, error, sizeof error), 1);
    EXPECT_EQ(first, 1u);  // the pillar hides light 0
    EXPECT_EQ(q3sh_test_c_light_cache(bsp.data(), 10, behind, &first, error, sizeof error), -1);
}

}  // namespace
}  // namespace q3::sh
