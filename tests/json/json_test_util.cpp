#include "json_test_util.h"

#include "file_io.h"

#include <gtest/gtest.h>

#include <cstring>

namespace q3::test {
namespace fs = std::filesystem;

bsp::Bsp smallBsp() {
    bsp::Bsp b;
    b.entities = bsp::unparseEntities({
        bsp::Entity{{{"classname", "worldspawn"}, {"message", "json test"}, {"gridsize", "64 64 128"}}},
        bsp::Entity{{{"classname", "info_player_deathmatch"}, {"origin", "0 0 24"}}},
    });
    bsp::Shader shader{};
    std::strcpy(shader.name, "textures/base_wall/concrete");
    shader.contentFlags = 1;
    b.shaders.push_back(shader);
    std::strcpy(shader.name, "textures/skies/blue");
    shader.contentFlags = 0;
    shader.surfaceFlags = 0x4 | 0x80 | 0x2000;  // sky, nodraw, nosteps
    b.shaders.push_back(shader);
    b.planes = {{{0, 0, 1}, 0}, {{0, 0, -1}, 0}};
    b.nodes = {bsp::Node{0, {-1, -2}, {-64, -64, -16}, {64, 64, 16}}};
    b.leafs = {bsp::Leaf{-1, 0, {-64, -64, -16}, {64, 64, 0}, 0, 0, 0, 1},
               bsp::Leaf{0, 0, {-64, -64, 0}, {64, 64, 16}, 0, 1, 1, 0}};
    b.leafSurfaces = {0};
    b.leafBrushes = {0};
    b.brushes = {bsp::Brush{0, 1, 0}};
    b.brushSides = {bsp::BrushSide{1, 0}};
    const float corners[4][2] = {{-64, -64}, {64, -64}, {64, 64}, {-64, 64}};
    for (int i = 0; i < 4; ++i) {
        bsp::DrawVert v{};
        v.xyz[0] = corners[i][0];
        v.xyz[1] = corners[i][1];
        v.st[0] = corners[i][0] / 128.0f + 0.1f;
        v.st[1] = corners[i][1] / 128.0f + 0.3f;
        v.lightmap[0] = (corners[i][0] + 64) / 1024.0f + 0.5f / 128;
        v.lightmap[1] = (corners[i][1] + 64) / 1024.0f + 0.5f / 128;
        v.normal[2] = 1;
        v.color[0] = 10 + i;
        v.color[1] = 20;
        v.color[2] = 30;
        v.color[3] = 255;
        b.drawVerts.push_back(v);
    }
    b.drawIndexes = {0, 1, 2, 0, 2, 3};
    bsp::Surface s{};
    s.shaderNum = 0;
    s.fogNum = -1;
    s.surfaceType = bsp::MST_PLANAR;
    s.numVerts = 4;
    s.numIndexes = 6;
    s.lightmapNum = 0;
    s.lightmapWidth = 9;
    s.lightmapHeight = 9;
    s.lightmapOrigin[0] = -64;
    s.lightmapOrigin[1] = -64;
    s.lightmapVecs[0][0] = 1.0f / 16;
    s.lightmapVecs[1][1] = 1.0f / 16;
    s.lightmapVecs[2][2] = 1;
    b.surfaces.push_back(s);
    b.models = {bsp::Model{{-64, -64, 0}, {64, 64, 0}, 0, 1, 0, 1}};
    b.lightmaps.resize(bsp::kLightmapPageBytes);
    for (size_t i = 0; i < b.lightmaps.size(); ++i) b.lightmaps[i] = static_cast<uint8_t>(i * 7 + 3);
    b.lightGrid.resize(3 * 3 * 1);
    for (size_t i = 0; i < b.lightGrid.size(); ++i)
        b.lightGrid[i] = bsp::GridPoint{{uint8_t(i), 2, 3}, {4, uint8_t(5 + i), 6}, {7, uint8_t(8 * i)}};
    b.visibility = {1, 0, 0, 0, 1, 0, 0, 0, 0xff};
    return b;
}

sh::GridSH smallShGrid(int bx, int by, int bz) {
    sh::GridSH g;
    for (int i = 0; i < 3; ++i) {
        g.mins[i] = -64.0f + i * 0.1f;
        g.size[i] = 32.0f;
    }
    g.bounds[0] = bx;
    g.bounds[1] = by;
    g.bounds[2] = bz;
    g.points.resize(static_cast<size_t>(bx) * by * bz);
    for (size_t p = 0; p < g.points.size(); ++p)
        for (int k = 0; k < 9; ++k)
            for (int c = 0; c < 3; ++c) g.points[p].coeffs[k][c] = 0.1f * float(p) + 0.01f * k - 0.003f * c + 1.0f / 3.0f;
    return g;
}

fs::path writeMap(const fs::path& dir, const std::string& name, const bsp::Bsp& bsp) {
    fs::create_directories(dir / "maps");
    fs::path path = dir / "maps" / (name + ".bsp");
    bsp::writeBsp(path, bsp);
    return path;
}

std::vector<uint8_t> unpackThenPack(const bsp::Bsp& bsp, const fs::path& folder, json::JsonOptions options) {
    Log log(false);
    json::unpackBsp(bsp, folder, options, log);
    return bsp::serializeBsp(json::packFolder(folder, options, log));
}

void replaceInFile(const fs::path& file, const std::string& from, const std::string& to) {
    std::string text = readFileText(file);
    size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << "'" << from << "' not in " << file;
    text.replace(at, from.size(), to);
    writeFileAtomic(file, text);
}

}  // namespace q3::test
