// Tiny BSP images for the light cache tests, written by hand: axis-aligned brushes, a complete
// tree over a short list of axial split planes (every leaf holds the brushes touching its region),
// a chosen cluster per leaf, an optional visibility lump, WORLDLIGHTS and an optional SH grid.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "sh_grid_lump.h"
#include "world_lights.h"

namespace q3::sh::test {

// Shaders of every test map, in this order.
enum TestShader : int32_t { kShaderSolid = 0, kShaderSky = 1, kShaderWater = 2, kShaderGlass = 3, kShaderCount = 4 };

struct TestBox {
    float mins[3];
    float maxs[3];
    int32_t shader = kShaderSolid;
};

struct TestSplit {
    int axis;
    float dist;
};

struct TestMap {
    std::vector<TestBox> boxes;
    std::vector<TestSplit> splits;  // node planes by depth: 2^splits.size() leaves
    // Cluster of a leaf from its region (clipped to +-8192); default 0.
    std::function<int32_t(const float mins[3], const float maxs[3])> cluster;
    int32_t numClusters = 1;
    std::function<bool(int32_t from, int32_t to)> visible;  // unset: no visibility lump
    std::vector<WorldLight> lights;
    std::optional<GridSH> grid;  // lump 18 of a v47 file when set, else a v46 file
};

// The lumps (index = lump number) and the WORLDLIGHTS lump image, before assembling.
struct TestLumps {
    std::vector<std::vector<uint8_t>> lumps;
    std::vector<uint8_t> worldLights;  // empty: no BSPX trailer
};

TestLumps testLumps(const TestMap& map);
std::vector<uint8_t> assembleTestBsp(const TestLumps& lumps);
std::vector<uint8_t> buildTestBsp(const TestMap& map);

// Inside: x, y in [-256, 256], z in [0, 256]; 16-unit walls, floor and ceiling (solid); a solid
// pillar x, y in [-32, 32] from floor to ceiling; one inverse-square point light at (-200, 0, 128)
// with intensity 40000 (1.0 at 200 units), cluster 0, not in the SH grid. One cluster, no
// visibility lump, no grid.
TestMap roomWithPillar();
WorldLight testPointLight(float x, float y, float z, float intensity);

}  // namespace q3::sh::test
