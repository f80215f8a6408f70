// The flow a mapper runs, on every oacmp map: the reference compiles the .map (-bsp -meta, then
// -vis -fast), ours lights the fresh BSP, whose surfaces all carry lightmapNum -3. The result must
// have lightmaps, relighting it must give the same file but for the recorded command line, and
// ioquake3 and DarkPlaces must load it strictly. Without the reference binary the tests skip (fail
// when $CI is set).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>

#include "bspfile.h"
#include "conformance_pipeline.h"
#include "reference_fixture.h"
#include "engine_run.h"
#include "file_io.h"
#include "test_data.h"

namespace q3::conformance {
namespace {
namespace fs = std::filesystem;

// The 13 maps of openarena-oacmp1; a sanitizer build (Q3MAP_TEST_MAP_STRIDE > 1) takes every Nth.
std::vector<std::string> mapNames() {
    const std::vector<std::string> all = {"oacmpctf1", "oacmpctf2", "oacmpctf3", "oacmpdm1",  "oacmpdm10",
                                          "oacmpdm2",  "oacmpdm3",  "oacmpdm4",  "oacmpdm5",  "oacmpdm6",
                                          "oacmpdm7",  "oacmpdm8",  "oacmpdm9"};
    std::vector<std::string> out;
    for (size_t i = 0; i < all.size(); i += size_t(std::max(1, Q3MAP_TEST_MAP_STRIDE))) out.push_back(all[i]);
    return out;
}

fs::path mapSource(const std::string& name) {
    for (const fs::path& p : test::oacmpMapSources())
        if (p.stem() == name) return p;
    throw std::runtime_error("no .map source named " + name);
}

template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every lump but the entities, and the entities but the command line each run appends.
void expectSameButCommandLine(const bsp::Bsp& a, const bsp::Bsp& b) {
    EXPECT_TRUE(sameBytes(a.shaders, b.shaders));
    EXPECT_TRUE(sameBytes(a.planes, b.planes));
    EXPECT_TRUE(sameBytes(a.nodes, b.nodes));
    EXPECT_TRUE(sameBytes(a.leafs, b.leafs));
    EXPECT_TRUE(sameBytes(a.models, b.models));
    EXPECT_TRUE(sameBytes(a.brushes, b.brushes));
    EXPECT_TRUE(sameBytes(a.drawVerts, b.drawVerts)) << "draw vertices (lightmap coordinates, colours)";
    EXPECT_TRUE(sameBytes(a.drawIndexes, b.drawIndexes));
    EXPECT_TRUE(sameBytes(a.surfaces, b.surfaces)) << "surfaces (lightmap numbers and rectangles)";
    EXPECT_TRUE(sameBytes(a.lightmaps, b.lightmaps)) << "lump 14";
    EXPECT_TRUE(sameBytes(a.lightGrid, b.lightGrid)) << "lump 15";
    EXPECT_TRUE(sameBytes(a.visibility, b.visibility));
    std::vector<bsp::Entity> ea = bsp::parseEntities(a.entities, "first");
    std::vector<bsp::Entity> eb = bsp::parseEntities(b.entities, "second");
    ASSERT_FALSE(ea.empty());
    ASSERT_FALSE(eb.empty());
    EXPECT_EQ(eb[0].value("_q3map2_cmdline"), ea[0].value("_q3map2_cmdline") + "; -light -fast");
    ea[0].set("_q3map2_cmdline", "");
    eb[0].set("_q3map2_cmdline", "");
    EXPECT_EQ(bsp::unparseEntities(ea), bsp::unparseEntities(eb));
}

class FreshPipeline : public ReferenceTest<std::string> {};

TEST_P(FreshPipeline, LightsRelightsIdenticallyAndLoadsInEngines) {
    const std::string name = GetParam();
    const fs::path& reference = this->reference();
    const fs::path gameBase = test::openArenaBase();
    const fs::path fresh = freshCompile(reference, gameBase, test::dataCache(), mapSource(name));
    const fs::path work = test::tempDir();

    const fs::path lit = stageFresh(fresh, work / "lit", name);
    const bsp::Bsp unlit = bsp::readBsp(lit);
    for (const bsp::Surface& s : unlit.surfaces) ASSERT_EQ(s.lightmapNum, bsp::kLightmapByVertex);
    const ToolRun first = lightWithOurs(test::q3map2Exe(), gameBase, lit, {"-fast"}, 2);
    ASSERT_EQ(first.exitCode, 0) << first.output;
    const bsp::Bsp once = bsp::readBsp(lit);
    int lightmapped = 0;
    for (const bsp::Surface& s : once.surfaces) lightmapped += s.lightmapNum >= 0;
    EXPECT_GT(lightmapped, int(once.surfaces.size()) / 2) << name << ": most surfaces get a lightmap";
    EXPECT_FALSE(once.lightmaps.empty());

    // Relit: a copy of the lit file in a folder of its own, with the same .srf and .map.
    const fs::path relit = stageFresh(fresh, work / "relit", name);
    fs::copy_file(lit, relit, fs::copy_options::overwrite_existing);
    const ToolRun second = lightWithOurs(test::q3map2Exe(), gameBase, relit, {"-fast"}, 2);
    ASSERT_EQ(second.exitCode, 0) << second.output;
    expectSameButCommandLine(once, bsp::readBsp(relit));

    enginetest::expectLoads(lit, "ioq3,dp", work / "engine-logs");
}

// The cache key names the reference by its contents: new timestamps keep the key, a changed byte
// in any file of its folder changes it.
TEST(FreshCacheKey, FollowsTheReferenceFolderContentsNotItsTimestamps) {
    const fs::path dir = fs::path(::testing::TempDir()) / "fresh-cache-key";
    fs::remove_all(dir);
    fs::create_directories(dir / "ref");
    writeFileAtomic(dir / "ref" / "q3map2", std::string("#!/bin/sh\n"));
    writeFileAtomic(dir / "ref" / "q3map2.x86_64", std::string("binary"));
    writeFileAtomic(dir / "m.map", std::string("{\n}\n"));
    const std::string key = freshCacheKey(dir / "ref" / "q3map2", dir / "m.map");
    EXPECT_EQ(key.rfind("m-", 0), 0u) << key;
    EXPECT_EQ(key.size(), 2u + 16u + 1u + 16u) << key;

    fs::last_write_time(dir / "ref" / "q3map2.x86_64", fs::file_time_type::clock::now() - std::chrono::hours(48));
    EXPECT_EQ(freshCacheKey(dir / "ref" / "q3map2", dir / "m.map"), key);

    writeFileAtomic(dir / "ref" / "q3map2.x86_64", std::string("binarY"));
    const std::string changed = freshCacheKey(dir / "ref" / "q3map2", dir / "m.map");
    EXPECT_NE(changed, key);
    EXPECT_EQ(changed.substr(changed.size() - 16), key.substr(key.size() - 16));  // same .map hash
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Oacmp, FreshPipeline, ::testing::ValuesIn(mapNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace q3::conformance
