// The VFS and the image decoders on the real OpenArena game tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <unzip.h>

#include "test_data.h"
#include "vfs_image.h"

namespace q3 {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// Every entry name of one archive, read with minizip directly (independent of the VFS index).
std::vector<std::string> zipEntryNames(const fs::path& pk3) {
    std::vector<std::string> names;
    unzFile zip = unzOpen64(pk3.string().c_str());
    if (!zip) return names;
    for (int status = unzGoToFirstFile(zip); status == UNZ_OK; status = unzGoToNextFile(zip)) {
        char name[1024];
        if (unzGetCurrentFileInfo64(zip, nullptr, name, sizeof name, nullptr, 0, nullptr, 0) == UNZ_OK)
            names.emplace_back(name);
    }
    unzClose(zip);
    return names;
}

// The archives of the game folder, in ascending case-insensitive name order.
std::vector<fs::path> baseoaArchives() {
    std::vector<fs::path> pk3s;
    for (const auto& entry : fs::directory_iterator(test::openArenaBase() / "baseoa"))
        if (lower(entry.path().extension().string()) == ".pk3") pk3s.push_back(entry.path());
    std::sort(pk3s.begin(), pk3s.end(), [](const fs::path& a, const fs::path& b) {
        return lower(a.filename().string()) < lower(b.filename().string());
    });
    return pk3s;
}

class OpenArena : public ::testing::Test {
protected:
    void SetUp() override {
        VfsOptions options;
        options.basePaths = {test::openArenaBase()};
        options.gameDirs = {"baseoa"};
        vfs_ = std::make_unique<Vfs>(options, log_);
    }
    Log log_{false};
    std::unique_ptr<Vfs> vfs_;
};

TEST_F(OpenArena, AllArchivesOpenInNameOrder) {
    std::vector<std::string> expected;
    for (const fs::path& pk3 : baseoaArchives()) expected.insert(expected.begin(), pk3.filename().string());
    ASSERT_GE(expected.size(), 5u);
    std::vector<std::string> names;
    for (const VfsSource& source : vfs_->sources())
        if (source.kind == VfsSource::Kind::Archive) names.push_back(source.location.filename().string());
    EXPECT_EQ(names, expected);
    EXPECT_EQ(log_.warningCount(), 0);
}

TEST_F(OpenArena, ListsEveryShaderScript) {
    // The archives' own tables of contents (read with minizip directly) say which scripts exist.
    std::set<std::string> expected;
    for (const fs::path& pk3 : baseoaArchives())
        for (const std::string& name : zipEntryNames(pk3)) {
            const std::string key = lower(name);
            if (key.starts_with("scripts/") && key.ends_with(".shader") && key.find('/', 8) == std::string::npos)
                expected.insert(key);
        }
    ASSERT_GT(expected.size(), 50u);
    const std::vector<std::string> listed = vfs_->list("scripts", "shader");
    std::set<std::string> got;
    for (const std::string& name : listed) got.insert(lower(name));
    EXPECT_EQ(got, expected);
    EXPECT_EQ(got.size(), listed.size());
    EXPECT_TRUE(std::is_sorted(listed.begin(), listed.end(),
                               [](const std::string& a, const std::string& b) { return lower(a) < lower(b); }));
    // Scripts read back with the bytes of their unpacked copies (loose/<package>/scripts/), for
    // every script whose highest-priority copy comes from that package.
    size_t compared = 0;
    for (const fs::path& script : test::allShaderScripts()) {
        const std::string package = script.parent_path().parent_path().filename().string();
        const std::string name = "scripts/" + script.filename().string();
        auto source = vfs_->sourceOf(name);
        if (!source || source->find("/" + package + ".pk3:") == std::string::npos) continue;
        auto bytes = vfs_->read(name);
        ASSERT_TRUE(bytes) << name;
        EXPECT_EQ(*bytes, readFileBytes(script)) << script;
        ++compared;
    }
    EXPECT_GT(compared, 50u);
}

TEST_F(OpenArena, LaterArchiveOverridesEarlierOne) {
    // levelshots/aggressor.tga ships in pak1-maps and again in pak6-patch088.
    auto source = vfs_->sourceOf("LevelShots/Aggressor.TGA");
    ASSERT_TRUE(source);
    EXPECT_NE(source->find("pak6-patch088.pk3:levelshots/aggressor.tga"), std::string::npos) << *source;
    EXPECT_EQ(vfs_->readAll("levelshots/aggressor.tga").size(), 2u);
}

TEST_F(OpenArena, DecodesKnownTextures) {
    // 32-bit uncompressed TGA; means computed independently from the file's raw BGRA bytes.
    auto tga = loadImage(*vfs_, "textures/acc_dm3/brwnwater");
    ASSERT_TRUE(tga);
    EXPECT_EQ(tga->path, "textures/acc_dm3/brwnwater.tga");
    EXPECT_EQ(tga->image.width, 256);
    EXPECT_EQ(tga->image.height, 256);
    const ImageAverage average = averageColor(tga->image);
    EXPECT_NEAR(average.mean[0], 117.974f, 0.01f);
    EXPECT_NEAR(average.mean[1], 123.726f, 0.01f);
    EXPECT_NEAR(average.mean[2], 83.119f, 0.01f);
    EXPECT_NEAR(average.mean[3], 51.0f, 0.01f);
    EXPECT_FLOAT_EQ(average.normalized[1], 1.0f);

    // levelshots/czest1dm.tga: a 256x256 RLE 24-bit copy in pak1-maps, replaced by a 128x128
    // uncompressed one in pak6-patch088.
    const auto copies = vfs_->readAll("levelshots/czest1dm.tga");
    ASSERT_EQ(copies.size(), 2u);
    const Image original = decodeImage(copies[0], "levelshots/czest1dm.tga");
    EXPECT_EQ(original.width, 256);
    EXPECT_EQ(original.height, 256);
    const Image replacement = decodeImage(*vfs_->read("levelshots/czest1dm.tga"), "levelshots/czest1dm.tga");
    EXPECT_EQ(replacement.width, 128);
    EXPECT_EQ(replacement.height, 128);
    // Means (and the top-left texel, to check orientation) computed independently from the files.
    const ImageAverage a = averageColor(original), b = averageColor(replacement);
    EXPECT_NEAR(a.mean[0], 52.3315f, 0.001f);
    EXPECT_NEAR(a.mean[1], 51.9934f, 0.001f);
    EXPECT_NEAR(a.mean[2], 46.8947f, 0.001f);
    EXPECT_FLOAT_EQ(a.mean[3], 255.0f);
    EXPECT_NEAR(b.mean[0], 35.1577f, 0.001f);
    EXPECT_NEAR(b.mean[1], 35.6227f, 0.001f);
    EXPECT_NEAR(b.mean[2], 34.5145f, 0.001f);
    EXPECT_EQ(sampleNearest(replacement, 0, 0), (std::array<uint8_t, 4>{40, 56, 64, 255}));
    auto rle32 = loadImage(*vfs_, "textures/base_floor/cybergrate2.tga");
    ASSERT_TRUE(rle32);
    EXPECT_EQ(rle32->image.width, 256);
    const ImageAverage grate = averageColor(rle32->image);
    EXPECT_NEAR(grate.mean[0], 36.9115f, 0.001f);
    EXPECT_NEAR(grate.mean[1], 32.1997f, 0.001f);
    EXPECT_NEAR(grate.mean[2], 28.9335f, 0.001f);
    EXPECT_NEAR(grate.mean[3], 129.2294f, 0.001f);  // a grate has see-through parts
    const auto topLeft = sampleNearest(rle32->image, 0, 0);
    EXPECT_EQ(topLeft[0], 27);
    EXPECT_EQ(topLeft[1], 23);
    EXPECT_EQ(topLeft[2], 24);

    // JPEG named with .tga in a shader: the fallback finds the .jpg.
    auto jpg = loadImage(*vfs_, "textures/acc_dm3/ceiling.tga");
    ASSERT_TRUE(jpg);
    EXPECT_EQ(jpg->path, "textures/acc_dm3/ceiling.jpg");
    EXPECT_EQ(jpg->image.width, 512);
    EXPECT_EQ(jpg->image.height, 512);
    const ImageAverage ceiling = averageColor(jpg->image);
    EXPECT_FLOAT_EQ(ceiling.mean[3], 255.0f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(ceiling.mean[c], 10.0f);
        EXPECT_LT(ceiling.mean[c], 245.0f);
    }
}

TEST_F(OpenArena, DecodesARealPng) {
    // pak0's team icons are 8-bit RGBA PNGs; means and centre texel computed independently.
    auto bytes = vfs_->read("icons/icona_red.png");
    ASSERT_TRUE(bytes);
    const Image png = decodeImage(*bytes, "icons/icona_red.png");
    EXPECT_EQ(png.width, 64);
    EXPECT_EQ(png.height, 64);
    const ImageAverage average = averageColor(png);
    EXPECT_NEAR(average.mean[0], 88.5254f, 0.001f);
    EXPECT_NEAR(average.mean[1], 6.1426f, 0.001f);
    EXPECT_NEAR(average.mean[2], 6.1426f, 0.001f);
    EXPECT_NEAR(average.mean[3], 73.1074f, 0.001f);
    EXPECT_EQ(sampleNearest(png, 0.5f, 0.5f), (std::array<uint8_t, 4>{245, 17, 17, 235}));
    // A TGA of the same name exists too, and q3map2's order prefers it even when the PNG is named.
    auto preferred = loadImage(*vfs_, "icons/icona_red.png");
    ASSERT_TRUE(preferred);
    EXPECT_EQ(preferred->path, "icons/icona_red.tga");
}

TEST_F(OpenArena, EveryShippedImageDecodes) {
    std::set<std::string> images;
    for (const VfsSource& source : vfs_->sources()) {
        if (source.kind != VfsSource::Kind::Archive) continue;
        for (const std::string& name : zipEntryNames(source.location))
            if (imageFormatFromName(name) != ImageFormat::Unknown) images.insert(lower(name));
    }
    ASSERT_GT(images.size(), 2000u);
    size_t tgas = 0, jpgs = 0, pngs = 0;
    for (const std::string& name : images) {
        auto bytes = vfs_->read(name);
        ASSERT_TRUE(bytes) << name;
        const Image image = decodeImage(*bytes, name);
        ASSERT_FALSE(image.empty()) << name;
        ASSERT_LE(image.width, kMaxImageDimension) << name;
        ASSERT_EQ(image.rgba.size(), size_t(image.width) * image.height * 4) << name;
        const ImageFormat format = imageFormatFromName(name);
        (format == ImageFormat::Tga ? tgas : format == ImageFormat::Png ? pngs : jpgs)++;
    }
    EXPECT_GT(tgas, 500u);
    EXPECT_GT(jpgs, 1000u);
    EXPECT_GE(pngs, 5u);
}

TEST(OpenArenaDetection, BasePathFromAMapInsideBaseoa) {
    const fs::path base = test::openArenaBase();
    VfsOptions options;
    options.mapPath = base / "baseoa" / "maps" / "oacmpdm1.bsp";  // need not exist
    Log log(false);
    Vfs vfs(options, log);
    ASSERT_EQ(vfs.basePaths().size(), 1u);
    EXPECT_EQ(fs::weakly_canonical(vfs.basePaths()[0]), fs::weakly_canonical(base));
    EXPECT_TRUE(vfs.exists("textures/acc_dm3/ceiling.jpg"));
    EXPECT_GT(vfs.list("scripts", "shader").size(), 50u);

    // The same tree with -fs_basegame baseoa: identical view.
    VfsOptions explicitOptions;
    explicitOptions.basePaths = {base};
    explicitOptions.baseGame = "baseoa";
    Vfs explicitVfs(explicitOptions, log);
    EXPECT_EQ(explicitVfs.list("scripts", "shader"), vfs.list("scripts", "shader"));
    EXPECT_EQ(log.warningCount(), 0);
}

}  // namespace
}  // namespace q3
