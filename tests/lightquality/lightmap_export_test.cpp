// Lightmap pages as pictures: orientation, -light -export, the -import round trip (byte-identical
// BSP), an edited PNG page changing the BSP's lightmap, bad pictures, and the -lightmapatlas PNG.
#include <gtest/gtest.h>

#include "image.h"
#include "lightmap_export.h"
#include "quality_scene.h"

namespace q3::light {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> patternPage(int size, int seed) {
    std::vector<uint8_t> page(static_cast<size_t>(size) * size * 3);
    for (size_t i = 0; i < page.size(); ++i) page[i] = static_cast<uint8_t>((i * 7 + static_cast<size_t>(seed) * 31) % 251);
    return page;
}

TEST(LightmapPictures, PageRowZeroIsTheBottomRowAndRoundTrips) {
    const std::vector<uint8_t> page = patternPage(128, 1);
    const Image picture = pagePicture(page, 128);
    ASSERT_EQ(picture.width, 128);
    ASSERT_EQ(picture.height, 128);
    EXPECT_EQ(picture.texel(5, 127)[0], page[5 * 3]);                    // row 0 -> bottom
    EXPECT_EQ(picture.texel(5, 0)[1], page[(127 * 128 + 5) * 3 + 1]);    // row 127 -> top
    EXPECT_EQ(picture.texel(5, 0)[3], 255);
    EXPECT_EQ(pageFromPicture(picture, 128, "p.tga"), page);
    // Through the TGA encoder and decoder too.
    const Image decoded = decodeTga(encodeTga(picture, false), "p.tga");
    EXPECT_EQ(pageFromPicture(decoded, 128, "p.tga"), page);
    EXPECT_EQ(exportedLightmapName(7), "lightmap_0007.tga");
    EXPECT_EQ(exportedLightmapName(12, "png"), "lightmap_0012.png");
    EXPECT_EQ(lightmapExportDir("base/maps/foo.bsp"), fs::path("base/maps/foo"));
}

TEST(LightmapPictures, WrongSizeOrBrokenLumpIsAnError) {
    Image small;
    small.width = small.height = 64;
    small.rgba.assign(64 * 64 * 4, 0);
    try {
        pageFromPicture(small, 128, "maps/x/lightmap_0000.png");
        FAIL() << "no error";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find("maps/x/lightmap_0000.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("64x64"), std::string::npos) << e.what();
    }
    bsp::Bsp b;
    b.lightmaps.assign(1000, 0);
    EXPECT_THROW(lumpPages(b, "maps/x.bsp"), bsp::BspError);
}

TEST(LightmapPictures, AtlasLaysPagesOutInAGrid) {
    std::vector<std::vector<uint8_t>> pages;
    for (int i = 0; i < 5; ++i) pages.push_back(patternPage(4, i));
    const Image atlas = lightmapAtlas(pages, 4);
    ASSERT_EQ(atlas.width, 12);  // 3 columns
    ASSERT_EQ(atlas.height, 8);  // 2 rows
    for (int p = 0; p < 5; ++p)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(atlas.texel((p % 3) * 4 + x, (p / 3) * 4 + y)[c],
                              pages[static_cast<size_t>(p)][static_cast<size_t>((y * 4 + x) * 3 + c)]);
    EXPECT_EQ(atlas.texel(9, 5)[0], 0);  // the empty sixth cell
    EXPECT_EQ(atlas.texel(9, 5)[3], 255);
    EXPECT_TRUE(lightmapAtlas({}, 128).empty());
}

// Floor with ambient light and a wall, darkened by dirt so that the page has detail.
fs::path litScene(const std::string& name, const std::vector<std::string>& args, bsp::Bsp* source = nullptr) {
    bsp::Bsp b = quality::emptyBsp({"textures/test/floor"});
    quality::addQuad(b, {0, 0, 0}, {0, 512, 0}, {512, 0, 0}, 0);
    quality::addQuad(b, {0, 0, 0}, {0, 0, 256}, {0, 512, 0}, 0);
    quality::finish(b, {{"_ambient", "120"}});
    if (source) *source = b;
    const fs::path path = quality::writeScene(b, name);
    EXPECT_EQ(quality::runLight(path, args), 0);
    return path;
}

int runPictureStage(const fs::path& bsp, bool import, Log& log) {
    CommonOptions common;
    common.mapPath = bsp;
    return import ? runImportStage(common, log) : runExportStage(common, log);
}

TEST(LightmapExport, LightExportWritesEveryPageWhereQ3map2Does) {
    const fs::path path = litScene("exported", {"-dirty", "-export"});
    const bsp::Bsp lit = bsp::readBsp(path);
    ASSERT_FALSE(lit.lightmaps.empty());
    const size_t pages = lit.lightmaps.size() / (128 * 128 * 3);
    const fs::path dir = path.parent_path() / "exported";
    for (size_t i = 0; i < pages; ++i) {
        const fs::path file = dir / exportedLightmapName(static_cast<int>(i));
        ASSERT_TRUE(fs::exists(file)) << file;
        const Image picture = decodeTga(readFileBytes(file), file.string());
        const std::vector<uint8_t> page = pageFromPicture(picture, 128, file.string());
        EXPECT_TRUE(std::equal(page.begin(), page.end(), lit.lightmaps.begin() + static_cast<long>(i * page.size())));
    }
    EXPECT_FALSE(fs::exists(dir / exportedLightmapName(static_cast<int>(pages))));
}

TEST(LightmapExport, ImportOfUneditedPagesIsByteIdentical) {
    const fs::path path = litScene("roundtrip", {"-dirty"});
    const std::vector<uint8_t> before = readFileBytes(path);
    Log log(false);
    ASSERT_EQ(runPictureStage(path, false, log), 0);
    ASSERT_TRUE(fs::exists(path.parent_path() / "roundtrip" / "lightmap_0000.tga"));
    EXPECT_EQ(readFileBytes(path), before) << "-export leaves the BSP alone";
    ASSERT_EQ(runPictureStage(path, true, log), 0);
    EXPECT_EQ(readFileBytes(path), before);
    EXPECT_EQ(log.warningCount(), 0);
}

TEST(LightmapExport, EditedPngPageChangesTheLightmap) {
    const fs::path path = litScene("edited", {"-dirty", "-export"});
    const bsp::Bsp lit = bsp::readBsp(path);
    const fs::path dir = path.parent_path() / "edited";
    const fs::path tga = dir / "lightmap_0000.tga";
    Image picture = decodeTga(readFileBytes(tga), tga.string());
    // Paint the floor's first luxel pure red, in the picture's own orientation.
    const bsp::Surface& floor = lit.surfaces[0];
    const int x = floor.lightmapX, row = floor.lightmapY;
    uint8_t* t = picture.texel(x, 127 - row);
    ASSERT_FALSE(t[0] == 255 && t[1] == 0 && t[2] == 0);
    t[0] = 255;
    t[1] = 0;
    t[2] = 0;
    fs::remove(tga);
    writeFileAtomic(dir / "lightmap_0000.png", encodePng(picture, false));

    Log log(false);
    ASSERT_EQ(runPictureStage(path, true, log), 0);
    const bsp::Bsp imported = bsp::readBsp(path);
    ASSERT_EQ(imported.lightmaps.size(), lit.lightmaps.size());
    const size_t at = (static_cast<size_t>(row) * 128 + static_cast<size_t>(x)) * 3;
    EXPECT_EQ(imported.lightmaps[at], 255);
    EXPECT_EQ(imported.lightmaps[at + 1], 0);
    EXPECT_EQ(imported.lightmaps[at + 2], 0);
    size_t differences = 0;
    for (size_t i = 0; i < lit.lightmaps.size(); ++i) differences += imported.lightmaps[i] != lit.lightmaps[i];
    EXPECT_GE(differences, 1u);
    EXPECT_LE(differences, 3u);
    EXPECT_EQ(quality::texel(imported, 0, 0, 0), (std::array<int, 3>{255, 0, 0}));
}

TEST(LightmapExport, MissingPictureKeepsPageAndWarns) {
    const fs::path path = litScene("missing", {"-dirty"});
    const std::vector<uint8_t> before = readFileBytes(path);
    fs::create_directories(path.parent_path() / "missing");
    Log log(false);
    ASSERT_EQ(runPictureStage(path, true, log), 0);
    EXPECT_GE(log.warningCount(), 1);
    bsp::Bsp original = bsp::parseBsp(before, "before");
    EXPECT_EQ(bsp::readBsp(path).lightmaps, original.lightmaps);
}

TEST(LightmapExport, WrongSizedPictureIsAOneLineError) {
    const fs::path path = litScene("wrongsize", {"-dirty"});
    const std::vector<uint8_t> before = readFileBytes(path);
    const fs::path dir = path.parent_path() / "wrongsize";
    fs::create_directories(dir);
    Image small;
    small.width = small.height = 32;
    small.rgba.assign(32 * 32 * 4, 9);
    writeFileAtomic(dir / "lightmap_0000.tga", encodeTga(small, false));
    Log log(false);
    try {
        runPictureStage(path, true, log);
        FAIL() << "no error";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("lightmap_0000.tga"), std::string::npos) << e.what();
    }
    EXPECT_EQ(readFileBytes(path), before) << "the BSP is untouched on error";
}

TEST(LightmapExport, AtlasOptionWritesThePackedPages) {
    const fs::path atlasPath = test::tempDir() / "atlas.png";
    const fs::path path = litScene("atlas", {"-dirty", "-lightmapatlas", atlasPath.string()});
    const bsp::Bsp lit = bsp::readBsp(path);
    ASSERT_TRUE(fs::exists(atlasPath));
    const Image atlas = decodePng(readFileBytes(atlasPath), atlasPath.string());
    const size_t pages = lit.lightmaps.size() / (128 * 128 * 3);
    ASSERT_EQ(pages, 1u);
    ASSERT_EQ(atlas.width, 128);
    ASSERT_EQ(atlas.height, 128);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(atlas.texel(x, y)[c], lit.lightmaps[static_cast<size_t>((y * 128 + x) * 3 + c)]);
    EXPECT_THROW(quality::lightOptions({"-lightmapatlas"}), cli::UsageError);
}

}  // namespace
}  // namespace q3::light
