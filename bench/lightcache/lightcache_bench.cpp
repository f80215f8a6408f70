// Times LightCache::query on a real map: lightcache_bench MAP.bsp [benchmark flags]. The map is
// one lit with -light -sh -worldlights; its WORLDLIGHTS flags are cleared in memory first, as a
// map compiled with its world lights left out of the SH grid would have them, so every light is a
// candidate (with the flags set, a query only samples the grid).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "le_bytes.h"
#include "light_cache.h"

namespace {

struct BenchMap {
    q3::sh::LightCache cache;
    std::vector<std::array<float, 3>> positions;  // points in the map's open space (cluster >= 0)
};

// Clears bit 0 of every record's flags in the image's WORLDLIGHTS lump.
bool clearInGridFlags(std::vector<uint8_t>& bsp) {
    q3::sh::BspDirectory dir;
    if (!q3::sh::readBspDirectory(bsp.data(), bsp.size(), dir).empty()) return false;
    q3::sh::ByteRange lump;
    bool found = false;
    if (!q3::sh::findBspxLump(bsp.data(), bsp.size(), dir, q3::sh::kWorldLightsLumpName, lump, found).empty() || !found)
        return false;
    uint8_t* base = bsp.data() + (lump.data - bsp.data());
    const uint32_t count = q3::sh::le::readU32(base + 8);
    for (uint32_t i = 0; i < count; ++i) {
        uint8_t* flags = base + q3::sh::kWorldLightsHeaderBytes + i * q3::sh::kWorldLightRecordBytes + 8;
        q3::sh::le::writeU32(flags, q3::sh::le::readU32(flags) & ~q3::sh::kWorldLightInShGrid);
    }
    return true;
}

// Every 48 units over the world bounds, kept when the leaf has a cluster: where models can be.
std::vector<std::array<float, 3>> openPositions(const q3::sh::LightCache& cache, const q3::sh::BspDirectory& dir) {
    float mins[3], maxs[3];
    std::vector<std::array<float, 3>> out;
    if (!q3::sh::readWorldBounds(dir, mins, maxs).empty()) return out;
    for (float z = mins[2] + 24; z < maxs[2]; z += 48)
        for (float y = mins[1] + 24; y < maxs[1]; y += 48)
            for (float x = mins[0] + 24; x < maxs[0]; x += 48) {
                const float p[3] = {x, y, z};
                const int32_t leaf = q3::sh::pointLeaf(cache.collision(), p);
                if (cache.collision().leafs[leaf].cluster >= 0) out.push_back({x, y, z});
            }
    return out;
}

void queryBenchmark(benchmark::State& state, const BenchMap* map, int maxLocal) {
    size_t next = 0;
    double local = 0, projected = 0, occluded = 0;
    for (auto _ : state) {
        const q3::sh::LightCacheResult r = map->cache.query(map->positions[next].data(), maxLocal);
        benchmark::DoNotOptimize(r);
        local += r.localCount;
        projected += r.projectedCount;
        occluded += r.occludedCount;
        next = next + 1 == map->positions.size() ? 0 : next + 1;
    }
    const double n = double(state.iterations());
    state.counters["local"] = local / n;
    state.counters["projected"] = projected / n;
    state.counters["occluded"] = occluded / n;
    state.counters["positions"] = double(map->positions.size());
}

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s MAP.bsp [benchmark flags]\n", argv[0]);
        return 2;
    }
    std::ifstream in(argv[1], std::ios::binary);
    std::vector<uint8_t> bsp((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!clearInGridFlags(bsp)) {
        std::fprintf(stderr, "%s: no readable WORLDLIGHTS lump (light the map with -worldlights)\n", argv[1]);
        return 1;
    }
    BenchMap map;
    if (const std::string err = map.cache.loadFromBsp(bsp.data(), bsp.size(), argv[1]); !err.empty()) {
        std::fprintf(stderr, "%s\n", err.c_str());
        return 1;
    }
    q3::sh::BspDirectory dir;
    q3::sh::readBspDirectory(bsp.data(), bsp.size(), dir);
    map.positions = openPositions(map.cache, dir);
    if (map.positions.empty()) {
        std::fprintf(stderr, "%s: no open positions\n", argv[1]);
        return 1;
    }
    std::printf("%zu lights, %zu nodes, %zu leaf brushes, %zu query positions\n", map.cache.lights().size(),
                map.cache.collision().nodes.size(), map.cache.collision().leafBrushes.size(), map.positions.size());
    benchmark::RegisterBenchmark("LightCacheQuery/4local", queryBenchmark, &map, 4)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("LightCacheQuery/0local", queryBenchmark, &map, 0)->Unit(benchmark::kMicrosecond);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
