// Light styles for IBSP: the pure pieces (MD4, shader body text, generated stages and shaders) and
// storeStyledLightmaps on a hand-built BSP whose style-0 blocks were packed by packLightmaps (page
// contents at the right texels, shader file, remapped surfaces, sharing, the 4-style limit,
// worldspawn _style<N>rgbgen/alphagen), plus -nostyles on entity lights.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bsp_scene.h"
#include "file_io.h"
#include "image.h"
#include "light_context.h"
#include "light_styles.h"
#include "lightmap_export.h"
#include "lightmap_pack.h"
#include "lights.h"
#include "log.h"
#include "option_parser.h"
#include "shader_loader.h"
#include "vfs.h"
#include "test_data.h"

namespace q3::light {
namespace {

namespace fs = std::filesystem;

std::string hex(const std::array<uint8_t, 16>& d) {
    static const char* digits = "0123456789abcdef";
    std::string s;
    for (uint8_t b : d) {
        s += digits[b >> 4];
        s += digits[b & 15];
    }
    return s;
}

TEST(StylesMd4, MatchesRfc1320Vectors) {
    EXPECT_EQ(hex(md4Digest("")), "31d6cfe0d16ae931b73c59d7e0c089c0");
    EXPECT_EQ(hex(md4Digest("a")), "bde52cb31de33e46245e05fbdbd6fb24");
    EXPECT_EQ(hex(md4Digest("abc")), "a448017aaf21d8525fc10ae87aa6729d");
    EXPECT_EQ(hex(md4Digest("message digest")), "d9130a8164549fe818874806e1c7014b");
    EXPECT_EQ(hex(md4Digest("abcdefghijklmnopqrstuvwxyz")), "d79e1c308aa5bbcdeea8ed63df412da9");
    EXPECT_EQ(hex(md4Digest("12345678901234567890123456789012345678901234567890123456789012345678901234567890")),
              "e33b4ddc9c38f2199c3e7b164fcc0536");
    EXPECT_EQ(generatedShaderName("dm1", "abc"), "dm1/A448017AAF21D8525FC10AE87AA6729D");
}

const char* kScript =
    "// comment line\n"
    "textures/test/plain\n"
    "{\n"
    "  qer_editorimage   textures/test/plain.tga   // trailing comment\n"
    "  {\n"
    "    map $lightmap\n"
    "    rgbGen identity\n"
    "  }\n"
    "}\n"
    "textures/test/marked\n"
    "{\n"
    "\tsurfaceparm nomarks\n"
    "\t{ map $lightmap\n"
    "\t  rgbGen identity }\n"
    "\tq3map_styleMarker\n"
    "\t{\n"
    "\t\tmap \"textures/test/marked.tga\"\n"
    "\t\tblendFunc GL_DST_COLOR GL_ZERO\n"
    "\t}\n"
    "}\n"
    "textures/test/compiler:q3map\n"
    "{\n"
    "\tq3map_surfacelight 100\n"
    "}\n";

TEST(StylesShaderText, BodyIsRetokenizedAsQ3map2KeepsIt) {
    std::optional<std::string> plain = shaderScriptBody(kScript, 2, "textures/test/plain");
    ASSERT_TRUE(plain);
    EXPECT_EQ(*plain, "\n{\n\tqer_editorimage textures/test/plain.tga\n\t{\n\t\tmap $lightmap\n\t\trgbGen identity\n\t}\n}\n");
    std::optional<std::string> marked = shaderScriptBody(kScript, 10, "TEXTURES/test/marked");
    ASSERT_TRUE(marked);
    EXPECT_EQ(*marked,
              "\n{\n\tsurfaceparm nomarks\n\t{\n\t\tmap $lightmap\n\t\trgbGen identity\n\t}\n\tq3map_styleMarker\n\t{\n"
              "\t\tmap textures/test/marked.tga\n\t\tblendFunc GL_DST_COLOR GL_ZERO\n\t}\n}\n");
    EXPECT_FALSE(shaderScriptBody(kScript, 21, "textures/test/compiler"));  // stageless :q3map keeps no text
    EXPECT_FALSE(shaderScriptBody(kScript, 3, "textures/test/plain"));      // not on that line
}

TEST(StylesShaderText, StagesDefaultsAndWorldspawnGens) {
    const std::vector<StyleStage> stages = {{1, "maps/m/lm_0000.tga"}, {5, "maps/m/lm_0001.tga"}};
    EXPECT_EQ(styleStagesText(stages, nullptr, false),
              "\n\t// Q3Map2 custom lightstyle stage(s)\n"
              "\t{\n\t\tmap maps/m/lm_0000.tga\n\t\tblendFunc GL_SRC_ALPHA GL_ONE\n"
              "\t\trgbGen wave noise 0.5 1 0 5.37 // style 1\n\t\ttcGen lightmap\n\t}\n"
              "\t{\n\t\tmap maps/m/lm_0001.tga\n\t\tblendFunc GL_SRC_ALPHA GL_ONE\n"
              "\t\trgbGen wave noise 0.5 1 0 5.37 // style 5\n\t\ttcGen lightmap\n\t}\n");
    bsp::Entity world;
    world.pairs = {{"classname", "worldspawn"}, {"_style5rgbgen", "wave sin 0.5 0.5 0 1"},
                   {"_style5alphagen", "wave square 0 1 0 2"}, {"_style1rgbgen", ""}};
    const std::string text = styleStagesText(stages, &world, true);
    EXPECT_NE(text.find("\t\tdepthFunc equal\n\t\trgbGen wave noise 0.5 1 0 5.37 // style 1\n"), std::string::npos);
    EXPECT_NE(text.find("\t\trgbGen wave sin 0.5 0.5 0 1 // style 5\n\t\talphaGen wave square 0 1 0 2 // style 5\n"
                        "\t\ttcGen lightmap\n"),
              std::string::npos);
    EXPECT_EQ(styleStageGens(&world, 1).rgbGen, std::string(kDefaultStyleRgbGen));  // empty value = default
    EXPECT_EQ(styleStageGens(&world, 1).alphaGen, "");
}

TEST(StylesShaderText, MarkerIsReplacedOrShaderKept) {
    EXPECT_EQ(generatedShaderText("\n{\n\tQ3MAP_STYLEMARKER\n}\n", 1, "<S>"), "\n{\n\t<S>\n}\n");
    EXPECT_EQ(generatedShaderText("\n{\n\tq3map_styleMarker2\n}\n", 2, "<S>"), "\n{\n\t<S>\n}\n");
    EXPECT_FALSE(generatedShaderText("\n{\n\t{\n\t\tmap $lightmap\n\t}\n}\n", 1, "<S>"));
    EXPECT_EQ(defaultShaderBody("textures/a/b"),
              "\n{ // Q3Map2 defaulted\n\t{\n\t\tmap $lightmap\n\t\trgbGen identity\n\t}\n\tq3map_styleMarker\n"
              "\t{\n\t\tmap textures/a/b.tga\n\t\tblendFunc GL_DST_COLOR GL_ZERO\n\t\trgbGen identity\n\t}\n}\n");
    EXPECT_EQ(generatedShaderFilePath("/q3/baseq3/maps/dm1.bsp"), fs::path("/q3/baseq3/scripts/q3map2_dm1.shader"));
}

// ---- storeStyledLightmaps on a hand-built map ----

constexpr int kBlockSize = 6;

// A BSP with `shaders` and one quad per entry of `surfaceShaders`, its context, and one 6x6
// style-0 block per surface whose texels are all different (never solid).
struct StyleScene {
    LightContext ctx;
    std::vector<LightmapBlock> blocks;
    PackedLightmaps packed;
    Log log{false};
    std::vector<std::string> messages;

    StyleScene(const std::vector<std::string>& shaders, const std::vector<int>& surfaceShaders, bool external = false,
               std::vector<std::pair<std::string, std::string>> worldKeys = {}, fs::path bspPath = {}) {
        log.addSink([this](LogLevel, std::string_view text) { messages.emplace_back(text); });
        // tempDir() empties the test's folder: a second scene of one test passes the first one's path.
        ctx.bspPath = bspPath.empty() ? test::tempDir() / "game" / "maps" / "stylemap.bsp" : bspPath;
        fs::create_directories(ctx.bspPath.parent_path());
        ctx.options.externalLightmaps = external;
        for (const std::string& name : shaders) {
            bsp::Shader s{};
            std::strncpy(s.name, name.c_str(), sizeof(s.name) - 1);
            s.contentFlags = 1;
            s.surfaceFlags = 0x10;
            ctx.bsp.shaders.push_back(s);
            LightingShader ls;
            ls.name = name;
            ctx.shaders.shaders.push_back(ls);
        }
        for (size_t i = 0; i < surfaceShaders.size(); ++i)
            test::addQuad(ctx.bsp, {float(i) * 200, 0, 0}, {0, 96, 0}, {96, 0, 0}, surfaceShaders[i]);
        bsp::Entity world;
        world.pairs = {{"classname", "worldspawn"}};
        for (auto& kv : worldKeys) world.pairs.push_back(kv);
        ctx.entities.push_back(world);
        for (size_t i = 0; i < surfaceShaders.size(); ++i) {
            LightmapBlock b;
            b.width = b.height = kBlockSize;
            for (int t = 0; t < kBlockSize * kBlockSize; ++t)
                b.texels.push_back({uint8_t(10 + t), uint8_t(i * 40), 7});
            b.sortKey = shaders[size_t(surfaceShaders[i])];
            b.surfaces = {int(i)};
            b.vertexCoords = {{{0, 0}, {6, 0}, {6, 6}, {0, 6}}};
            blocks.push_back(std::move(b));
        }
        PackOptions options;
        options.collapse = false;
        options.external = external;
        packed = packLightmaps(blocks, options);
        applyPackedLightmaps(ctx.bsp, blocks, packed);
        if (external) writeExternalLightmaps(packed, externalLightmapDir(ctx.bspPath, ""));
    }

    // Linear light that converts to `value` bytes everywhere (default colour options).
    StyledLightmap styled(int block, int style, float value) const {
        StyledLightmap s;
        s.block = block;
        s.style = style;
        s.width = s.height = kBlockSize;
        s.color.assign(kBlockSize * kBlockSize, Vec3{value, value / 2, 0});
        return s;
    }

    void store(std::vector<StyledLightmap> styled) { storeStyledLightmaps(ctx, blocks, packed, std::move(styled), log); }

    fs::path page(int n) const { return externalLightmapDir(ctx.bspPath, "") / externalLightmapName(n); }
    std::vector<uint8_t> pageBytes(int n) const {
        // Page row y is picture row y: the page is stored as the engine uploads it (tcGen lightmap).
        const Image picture = decodeTga(readFileBytes(page(n)), page(n).string());
        EXPECT_EQ(picture.width, packed.pageSize);
        EXPECT_EQ(picture.height, packed.pageSize);
        std::vector<uint8_t> rgb;
        for (size_t i = 0; i < picture.rgba.size(); i += 4) rgb.insert(rgb.end(), &picture.rgba[i], &picture.rgba[i + 3]);
        return rgb;
    }
    std::string shaderName(int surface) const {
        const bsp::Shader& s = ctx.bsp.shaders.at(size_t(ctx.bsp.surfaces.at(size_t(surface)).shaderNum));
        return std::string(s.name, strnlen(s.name, sizeof(s.name)));
    }
    std::string shaderFile() const { return readFileText(generatedShaderFilePath(ctx.bspPath)); }
    bool logged(std::string_view fragment) const {
        for (const std::string& m : messages)
            if (m.find(fragment) != std::string::npos) return true;
        return false;
    }
};

TEST(StylesStore, StyledBlockGoesToItsTexelsOnAnExternalPage) {
    StyleScene scene({"textures/test/wall"}, {0, 0});
    ASSERT_FALSE(scene.packed.external);
    ASSERT_EQ(scene.packed.pages.size(), 1u);
    const BlockPlacement place = scene.packed.placements[1];
    ASSERT_FALSE(place.solid);
    StyledLightmap s = scene.styled(1, 3, 100);
    s.color[size_t(2 * kBlockSize + 4)] = Vec3{200, 0, 50};  // luxel (4, 2)
    scene.store({s});

    ASSERT_TRUE(fs::exists(scene.page(0)));  // internal style-0 pages: styled pages start at lm_0000
    EXPECT_FALSE(fs::exists(scene.page(1)));
    const std::vector<uint8_t> rgb = scene.pageBytes(0);
    auto at = [&](int x, int y) {
        const size_t i = (size_t(y) * size_t(scene.packed.pageSize) + size_t(x)) * 3;
        return std::array<int, 3>{rgb[i], rgb[i + 1], rgb[i + 2]};
    };
    EXPECT_EQ(at(place.x, place.y), (std::array<int, 3>{100, 50, 0}));
    EXPECT_EQ(at(place.x + 4, place.y + 2), (std::array<int, 3>{200, 0, 50}));
    EXPECT_EQ(at(place.x + kBlockSize - 1, place.y + kBlockSize - 1), (std::array<int, 3>{100, 50, 0}));
    // Block 0 carries no styled light: its texels stay black.
    const BlockPlacement other = scene.packed.placements[0];
    EXPECT_EQ(at(other.x + 1, other.y + 1), (std::array<int, 3>{0, 0, 0}));
    // The style-0 lump is untouched.
    EXPECT_EQ(scene.ctx.bsp.lightmaps, scene.packed.lump14());
}

TEST(StylesStore, SurfaceRemappedToGeneratedShaderWrittenToTheMapScript) {
    StyleScene scene({"textures/test/wall"}, {0, 0});
    scene.store({scene.styled(1, 2, 80)});
    EXPECT_EQ(scene.shaderName(0), "textures/test/wall");
    const std::string name = scene.shaderName(1);
    ASSERT_EQ(scene.ctx.bsp.shaders.size(), 2u);
    EXPECT_EQ(scene.ctx.bsp.surfaces[1].shaderNum, 1);
    EXPECT_EQ(scene.ctx.bsp.shaders[1].contentFlags, 1);
    EXPECT_EQ(scene.ctx.bsp.shaders[1].surfaceFlags, 0x10);
    // No shader table: the surface's shader gets q3map2's default text with the marker replaced.
    const std::string stages = styleStagesText(std::vector<StyleStage>{{2, "maps/stylemap/lm_0000.tga"}}, nullptr, false);
    const std::optional<std::string> text = generatedShaderText(defaultShaderBody("textures/test/wall"), 1, stages);
    ASSERT_TRUE(text);
    EXPECT_EQ(name, generatedShaderName("stylemap", *text));
    const std::string file = scene.shaderFile();
    EXPECT_EQ(file.rfind("//", 0), 0u);
    EXPECT_NE(file.find(name + *text), std::string::npos);
    EXPECT_NE(file.find("\t\tmap maps/stylemap/lm_0000.tga\n\t\tblendFunc GL_SRC_ALPHA GL_ONE\n"
                        "\t\trgbGen wave noise 0.5 1 0 5.37 // style 2\n\t\ttcGen lightmap\n"),
              std::string::npos);
    EXPECT_EQ(file.find("q3map_styleMarker"), std::string::npos);
}

TEST(StylesStore, PagesAndShadersAreSharedByPageStyleAndShader) {
    // Surfaces 0..2 share shader 0, surface 3 uses shader 1; all blocks land on page 0.
    StyleScene scene({"textures/test/a", "textures/test/b"}, {0, 0, 0, 1});
    ASSERT_EQ(scene.packed.pages.size(), 1u);
    scene.store({scene.styled(0, 1, 60), scene.styled(1, 1, 90), scene.styled(2, 4, 30), scene.styled(3, 1, 40)});
    // Style 1 (blocks 0, 1, 3) shares lm_0000, style 4 gets lm_0001.
    EXPECT_TRUE(fs::exists(scene.page(0)));
    EXPECT_TRUE(fs::exists(scene.page(1)));
    EXPECT_FALSE(fs::exists(scene.page(2)));
    const std::vector<uint8_t> style1 = scene.pageBytes(0);
    for (int block : {0, 1, 3}) {
        const BlockPlacement p = scene.packed.placements[size_t(block)];
        const size_t i = (size_t(p.y) * size_t(scene.packed.pageSize) + size_t(p.x)) * 3;
        EXPECT_EQ(style1[i], block == 0 ? 60 : block == 1 ? 90 : 40) << block;
    }
    // Same shader and same (style, page) list: one generated shader; other shader or styles: another.
    EXPECT_EQ(scene.shaderName(0), scene.shaderName(1));
    EXPECT_NE(scene.shaderName(0), scene.shaderName(2));
    EXPECT_NE(scene.shaderName(0), scene.shaderName(3));
    EXPECT_EQ(scene.ctx.bsp.shaders.size(), 5u);
}

TEST(StylesStore, PerSurfaceStyleLimitKeepsTheThreeLowestStyles) {
    StyleScene scene({"textures/test/wall"}, {0});
    const int before = scene.log.warningCount();
    scene.store({scene.styled(0, 9, 50), scene.styled(0, 2, 50), scene.styled(0, 7, 50), scene.styled(0, 5, 50),
                 scene.styled(0, 2, 20)});
    EXPECT_EQ(scene.log.warningCount(), before + 1);
    EXPECT_TRUE(scene.logged("Hit per-surface style limit (4)"));
    EXPECT_TRUE(scene.logged("style 9 dropped"));
    const std::string file = scene.shaderFile();
    EXPECT_NE(file.find("// style 2\n"), std::string::npos);
    EXPECT_NE(file.find("// style 5\n"), std::string::npos);
    EXPECT_NE(file.find("// style 7\n"), std::string::npos);
    EXPECT_EQ(file.find("// style 9\n"), std::string::npos);
    // Stages in style order; the style given twice is summed (50 + 20).
    EXPECT_LT(file.find("// style 2\n"), file.find("// style 5\n"));
    const BlockPlacement p = scene.packed.placements[0];
    const std::vector<uint8_t> style2 = scene.pageBytes(0);
    EXPECT_EQ(style2[(size_t(p.y) * size_t(scene.packed.pageSize) + size_t(p.x)) * 3], 70);
    EXPECT_FALSE(fs::exists(scene.page(3)));
}

TEST(StylesStore, WorldspawnRgbGenAndAlphaGenReplaceTheDefaults) {
    StyleScene scene({"textures/test/wall"}, {0}, false,
                     {{"_style1rgbgen", "wave sin 0.5 0.5 0 1"}, {"_style1alphagen", "const 0.5"}});
    scene.store({scene.styled(0, 1, 50), scene.styled(0, 3, 50)});
    const std::string file = scene.shaderFile();
    EXPECT_NE(file.find("\t\trgbGen wave sin 0.5 0.5 0 1 // style 1\n\t\talphaGen const 0.5 // style 1\n"),
              std::string::npos);
    EXPECT_NE(file.find("\t\trgbGen wave noise 0.5 1 0 5.37 // style 3\n\t\ttcGen lightmap\n"), std::string::npos);
}

TEST(StylesStore, ExternalStyleZeroPagesComeFirst) {
    StyleScene scene({"textures/test/wall"}, {0, 0}, true);
    ASSERT_TRUE(scene.packed.external);
    const int style0Pages = int(scene.packed.pages.size());
    ASSERT_TRUE(fs::exists(scene.page(style0Pages - 1)));
    const std::vector<uint8_t> before = readFileBytes(scene.page(0));
    scene.store({scene.styled(0, 1, 50)});
    EXPECT_TRUE(fs::exists(scene.page(style0Pages)));
    EXPECT_EQ(readFileBytes(scene.page(0)), before);
    EXPECT_NE(scene.shaderFile().find("map maps/stylemap/" + externalLightmapName(style0Pages)), std::string::npos);
}

TEST(StylesStore, ScriptShaderWithMarker2GetsDepthFuncEqualAndOneWithoutIsKept) {
    StyleScene scene({"textures/test/marked", "textures/test/plain"}, {0, 1});
    const fs::path game = scene.ctx.bspPath.parent_path().parent_path();
    fs::create_directories(game / "scripts");
    std::string script = kScript;
    const size_t at = script.find("\tq3map_styleMarker\n");
    script.replace(at, std::string("\tq3map_styleMarker\n").size(), "\tq3map_styleMarker2\n");
    writeFileAtomic(game / "scripts" / "test.shader", script);
    VfsOptions vfsOptions;
    vfsOptions.mapPath = scene.ctx.bspPath;  // <tmp>/game/maps/stylemap.bsp: "game" becomes the mod folder
    scene.ctx.vfs = std::make_unique<Vfs>(vfsOptions, scene.log);
    scene.ctx.shaderTable = std::make_unique<ShaderTable>(loadShaderTable(*scene.ctx.vfs, scene.log));
    ASSERT_NE(scene.ctx.shaderTable->findExplicit("textures/test/marked"), nullptr);

    scene.store({scene.styled(0, 1, 50), scene.styled(1, 1, 50)});
    const std::string name = scene.shaderName(0);
    EXPECT_EQ(name.rfind("stylemap/", 0), 0u);
    EXPECT_EQ(scene.shaderName(1), "textures/test/plain");
    EXPECT_TRUE(scene.logged("textures/test/plain has no q3map_styleMarker"));
    const std::string file = scene.shaderFile();
    const std::string expectedText =
        "\n{\n\tsurfaceparm nomarks\n\t{\n\t\tmap $lightmap\n\t\trgbGen identity\n\t}\n\t"
        "\n\t// Q3Map2 custom lightstyle stage(s)\n\t{\n\t\tmap maps/stylemap/lm_0000.tga\n"
        "\t\tblendFunc GL_SRC_ALPHA GL_ONE\n\t\tdepthFunc equal\n\t\trgbGen wave noise 0.5 1 0 5.37 // style 1\n"
        "\t\ttcGen lightmap\n\t}\n\n\t{\n\t\tmap textures/test/marked.tga\n\t\tblendFunc GL_DST_COLOR GL_ZERO\n\t}\n}\n";
    EXPECT_EQ(name, generatedShaderName("stylemap", expectedText));
    EXPECT_NE(file.find(name + expectedText), std::string::npos);
}

TEST(StylesStore, BlackStyledLightAndBadInput) {
    StyleScene scene({"textures/test/wall"}, {0});
    scene.store({scene.styled(0, 1, 0.2f)});  // converts to zero bytes: nothing to draw
    EXPECT_FALSE(fs::exists(scene.page(0)));
    EXPECT_EQ(scene.shaderName(0), "textures/test/wall");
    EXPECT_THROW(scene.store({scene.styled(5, 1, 50)}), CompileError);
    EXPECT_THROW(scene.store({scene.styled(0, 0, 50)}), CompileError);
    StyledLightmap wrongSize = scene.styled(0, 1, 50);
    wrongSize.color.pop_back();
    EXPECT_THROW(scene.store({wrongSize}), CompileError);
    scene.blocks[0].surfaces = {7};
    EXPECT_THROW(scene.store({scene.styled(0, 1, 50)}), CompileError);
}

TEST(StylesStore, RunWithoutStyledLightRemovesTheOutputsOfAnEarlierRun) {
    StyleScene scene({"textures/test/wall"}, {0, 0});
    scene.store({scene.styled(0, 1, 50), scene.styled(1, 2, 50)});
    ASSERT_TRUE(fs::exists(scene.page(1)));
    ASSERT_TRUE(fs::exists(generatedShaderFilePath(scene.ctx.bspPath)));
    StyleScene again({"textures/test/wall"}, {0, 0}, false, {}, scene.ctx.bspPath);  // style-0 pages in lump 14
    ASSERT_TRUE(fs::exists(again.page(1)));
    again.store({});
    EXPECT_FALSE(fs::exists(again.page(0)));
    EXPECT_FALSE(fs::exists(again.page(1)));
    EXPECT_FALSE(fs::exists(generatedShaderFilePath(again.ctx.bspPath)));
    // A shader file this stage did not write stays.
    writeFileAtomic(generatedShaderFilePath(again.ctx.bspPath), std::string("// hand-written\n"));
    again.store({});
    EXPECT_TRUE(fs::exists(generatedShaderFilePath(again.ctx.bspPath)));
}

// ---- -nostyles ----

TEST(StylesNoStyles, OptionParsesAndZeroesEntityStyles) {
    LightOptions options;
    cli::parseOptions(lightOptionTable(), std::vector<std::string>{"-nostyles"}, cli::ParseContext{"-light", {}, {}}, options);
    EXPECT_TRUE(options.noStyles);
    cli::parseOptions(lightOptionTable(), std::vector<std::string>{"-styles"}, cli::ParseContext{"-light", {}, {}}, options);
    EXPECT_FALSE(options.noStyles);
    for (const auto& option : lightOptionTable()) {
        for (const std::string& name : option.info.names) {
            if (name == "-nostyles" || name == "-styles" || name == "-nostyle" || name == "-style") {
                EXPECT_TRUE(option.info.implemented) << name;
            }
        }
    }

    std::vector<bsp::Entity> entities(2);
    entities[0].pairs = {{"classname", "worldspawn"}};
    entities[1].pairs = {{"classname", "light"}, {"origin", "0 0 64"}, {"_style", "2"}};
    Log log(false);
    LightScales scales;
    CLibraryRandom random;
    std::vector<Light> styled = createEntityLights(entities, entities, scales, log, "styles.bsp", random);
    ASSERT_EQ(styled.size(), 1u);
    EXPECT_EQ(styled[0].style, 2);
    scales.noStyles = lightScalesFromOptions(options).noStyles;
    EXPECT_FALSE(scales.noStyles);
    LightOptions noStyles;
    noStyles.noStyles = true;
    scales = lightScalesFromOptions(noStyles);
    std::vector<Light> plain = createEntityLights(entities, entities, scales, log, "styles.bsp", random);
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_EQ(plain[0].style, 0);
}

TEST(StylesNoStyles, ShaderSunsAndSurfaceLightsLoseTheirStyle) {
    SunDirective sun;
    sun.intensity = 100;
    sun.style = 4;
    LightingShader emitter;
    emitter.surfaceLight = 500;
    emitter.lightStyle = 6;
    EmitterGeometry square;
    square.xyz = {{0, 0, 0}, {64, 0, 0}, {64, 64, 0}, {0, 64, 0}};
    square.normals.assign(4, Vec3{0, 0, 1});
    square.triangles = {0, 1, 2, 0, 2, 3};
    for (bool noStyles : {false, true}) {
        LightScales scales;
        scales.noStyles = noStyles;
        std::vector<Light> lights;
        CLibraryRandom random;
        appendSunLights(lights, sun, -1, scales, random);
        appendAreaLights(lights, square, emitter, scales);
        ASSERT_GE(lights.size(), 2u);
        for (const Light& light : lights) {
            const int expected = noStyles ? 0 : light.type == LightType::Sun ? 4 : 6;
            EXPECT_EQ(light.style, expected) << "noStyles " << noStyles;
        }
    }
}

}  // namespace
}  // namespace q3::light
