// "A styled light appears only in its style", through the q3map2 executable: a long floor lit by a
// plain light at one end and a `_style 1` light at the other. The style-0 lightmap must be dark
// under the styled light, the external styled page bright there and dark under the plain light,
// and the floor must be drawn through a generated shader that adds that page.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bsp_scene.h"
#include "bspfile.h"
#include "file_io.h"
#include "image.h"
#include "light_styles.h"
#include "lightmap_export.h"
#include "lightmap_pack.h"
#include "test_data.h"

namespace q3::light {
namespace {

namespace fs = std::filesystem;

constexpr float kFloorLength = 1024;  // along x
constexpr float kFloorWidth = 256;    // along y

fs::path writeStyleMap() {
    bsp::Bsp b;
    b.version = bsp::kVersionQ3;
    b.headerLumps = 18;
    bsp::Shader floor{};
    std::strncpy(floor.name, "textures/styletest/floor", sizeof(floor.name) - 1);
    floor.contentFlags = 1;
    b.shaders.push_back(floor);
    // Corner, then +y and +x edges: the normal cross(edgeV, edgeU) points up.
    test::addQuad(b, {0, 0, 0}, {0, kFloorWidth, 0}, {kFloorLength, 0, 0}, 0);
    bsp::Model world{};
    const float mins[3] = {0, 0, -8}, maxs[3] = {kFloorLength, kFloorWidth, 8};
    std::memcpy(world.mins, mins, sizeof(mins));
    std::memcpy(world.maxs, maxs, sizeof(maxs));
    world.numSurfaces = 1;
    b.models.push_back(world);
    std::vector<bsp::Entity> ents(3);
    ents[0].pairs = {{"classname", "worldspawn"}};
    ents[1].pairs = {{"classname", "light"}, {"origin", "96 128 64"}, {"light", "300"}};
    ents[2].pairs = {{"classname", "light"}, {"origin", "928 128 64"}, {"light", "300"}, {"_style", "1"}};
    b.entities = bsp::unparseEntities(ents);

    const fs::path maps = test::tempDir() / "stylegame" / "maps";
    fs::create_directories(maps);
    const fs::path path = maps / "styled.bsp";
    writeFileAtomic(path, bsp::serializeBsp(b));
    return path;
}

// Texel of the floor at world (x, y) on a page: bilinear in the quad's vertex lightmap coordinates.
std::array<int, 3> floorTexel(const bsp::Bsp& b, std::span<const uint8_t> page, int pageSize, float x, float y) {
    const bsp::Surface& s = b.surfaces.at(0);
    const float u = y / kFloorWidth, v = x / kFloorLength;  // vertex order: corner, +U, +U+V, +V
    const float w[4] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
    float st[2] = {0, 0};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 2; ++k) st[k] += w[i] * b.drawVerts.at(size_t(s.firstVert + i)).lightmap[k];
    const int px = std::clamp(int(st[0] * float(pageSize)), 0, pageSize - 1);
    const int py = std::clamp(int(st[1] * float(pageSize)), 0, pageSize - 1);
    const size_t at = (size_t(py) * size_t(pageSize) + size_t(px)) * 3;
    return {page[at], page[at + 1], page[at + 2]};
}

TEST(StylesEndToEnd, StyledLightAppearsOnlyInItsStyle) {
    const fs::path bspPath = writeStyleMap();
    std::string output;
    const int status = test::runCommand(test::q3map2Exe().string() + " -light " + bspPath.string(), &output);
    ASSERT_EQ(status, 0) << output;

    const bsp::Bsp lit = bsp::parseBsp(readFileBytes(bspPath), bspPath.string());
    const bsp::Surface& floor = lit.surfaces.at(0);
    ASSERT_GE(floor.lightmapNum, 0);
    ASSERT_EQ(lit.lightmaps.size() % (128 * 128 * 3), 0u);
    const std::span<const uint8_t> style0(lit.lightmaps.data() + size_t(floor.lightmapNum) * 128 * 128 * 3,
                                          128 * 128 * 3);
    const auto underPlain = floorTexel(lit, style0, 128, 96, 128);
    const auto underStyled = floorTexel(lit, style0, 128, 928, 128);
    EXPECT_GT(underPlain[0], 100) << "plain light missing from style 0";
    EXPECT_LT(underStyled[0], 20) << "styled light leaked into style 0";

    // The styled page: lm_0000.tga next to the BSP (style-0 pages are in lump 14).
    const fs::path pagePath = externalLightmapDir(bspPath, "") / externalLightmapName(0);
    ASSERT_TRUE(fs::exists(pagePath)) << output;
    const Image picture = decodeTga(readFileBytes(pagePath), pagePath.string());
    ASSERT_EQ(picture.width, 128);
    ASSERT_EQ(picture.height, 128);
    std::vector<uint8_t> styled;  // page row y is picture row y, as the engine uploads the page
    for (size_t i = 0; i < picture.rgba.size(); i += 4)
        styled.insert(styled.end(), &picture.rgba[i], &picture.rgba[i + 3]);
    EXPECT_GT(floorTexel(lit, styled, 128, 928, 128)[0], 100) << "styled light missing from its page";
    EXPECT_LT(floorTexel(lit, styled, 128, 96, 128)[0], 20) << "plain light leaked into the styled page";

    // The floor is drawn through a generated shader that adds the styled page.
    const bsp::Shader& shader = lit.shaders.at(size_t(floor.shaderNum));
    const std::string name(shader.name, strnlen(shader.name, sizeof(shader.name)));
    EXPECT_EQ(name.rfind("styled/", 0), 0u) << name;
    const fs::path script = generatedShaderFilePath(bspPath);
    ASSERT_TRUE(fs::exists(script));
    const std::string text = readFileText(script);
    EXPECT_NE(text.find(name + "\n{"), std::string::npos);
    EXPECT_NE(text.find("map maps/styled/lm_0000.tga"), std::string::npos);
}

}  // namespace
}  // namespace q3::light
