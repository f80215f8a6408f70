// Image loading through the VFS: extension fallback, JPEG alpha companions, error messages.
#include <gtest/gtest.h>

#include "test_data.h"
#include "vfs_image.h"
#include "zip_builder.h"

namespace q3 {
namespace {

namespace fs = std::filesystem;

Image checker(int width, int height, uint8_t value) {
    Image image;
    image.width = width;
    image.height = height;
    for (int i = 0; i < width * height; ++i) image.rgba.insert(image.rgba.end(), {value, uint8_t(i), 7, 255});
    return image;
}

std::string asString(const std::vector<uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

TEST(ImageCandidates, Q3map2Order) {
    EXPECT_EQ(imageCandidates("textures/a/b.jpg"),
              (std::vector<std::string>{"textures/a/b.tga", "textures/a/b.png", "textures/a/b.jpg", "textures/a/b.jpeg"}));
    EXPECT_EQ(imageCandidates("textures/a.b/c"),
              (std::vector<std::string>{"textures/a.b/c.tga", "textures/a.b/c.png", "textures/a.b/c.jpg",
                                        "textures/a.b/c.jpeg"}));
    EXPECT_TRUE(imageCandidates("").empty());
}

class VfsImageTest : public ::testing::Test {
protected:
    void SetUp() override {
        base_ = test::tempDir();
        // The shader says .tga but only a PNG exists; another has both TGA and PNG.
        test::writeZip(base_ / "baseq3/pak0.pk3",
                       {{"textures/t/only_png.png", asString(encodePng(checker(4, 2, 10), true))},
                        {"textures/t/both.png", asString(encodePng(checker(2, 2, 20), true))},
                        {"textures/t/both.tga", asString(encodeTga(checker(3, 3, 30), true))},
                        {"textures/t/broken.tga", "not an image"}});
        test::writeZip(base_ / "baseq3/pak1.pk3",
                       {{"textures/t/glass.jpg", asString(encodePng(checker(8, 8, 40), false))}});
        test::writeLoose(base_ / "baseq3/textures/t/glass_alpha.jpg", asString(encodePng(alphaSource(), false)));
        VfsOptions options;
        options.basePaths = {base_};
        vfs_ = std::make_unique<Vfs>(options, log_);
    }

    // Blue channel carries the alpha for the JPEG companion.
    static Image alphaSource() {
        Image image = checker(8, 8, 0);
        for (size_t i = 0; i < image.rgba.size(); i += 4) image.rgba[i + 2] = uint8_t(i);
        return image;
    }

    fs::path base_;
    Log log_{false};
    std::unique_ptr<Vfs> vfs_;
};

TEST_F(VfsImageTest, FallsBackToOtherExtensions) {
    auto loaded = loadImage(*vfs_, "textures/t/only_png.tga");
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->path, "textures/t/only_png.png");
    EXPECT_EQ(loaded->image.width, 4);
    EXPECT_EQ(loaded->image.rgba, checker(4, 2, 10).rgba);
    auto noExtension = loadImage(*vfs_, "TEXTURES/T/ONLY_PNG");
    ASSERT_TRUE(noExtension);
    EXPECT_EQ(noExtension->image.rgba, loaded->image.rgba);
}

TEST_F(VfsImageTest, TgaIsPreferredEvenWhenThePngIsNamed) {
    auto loaded = loadImage(*vfs_, "textures/t/both.png");
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->path, "textures/t/both.tga");
    EXPECT_EQ(loaded->image.width, 3);
}

TEST_F(VfsImageTest, JpegTakesAlphaFromTheBlueOfItsCompanion) {
    // Both files hold PNG bytes: decoding goes by content, the alpha rule by the .jpg name.
    auto loaded = loadImage(*vfs_, "textures/t/glass.tga");
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->path, "textures/t/glass.jpg");
    const Image alpha = alphaSource();
    for (size_t i = 0; i < loaded->image.rgba.size(); i += 4) {
        ASSERT_EQ(loaded->image.rgba[i + 3], alpha.rgba[i + 2]);
        ASSERT_EQ(loaded->image.rgba[i], 40);
    }
}

TEST_F(VfsImageTest, MissingAndMalformed) {
    EXPECT_FALSE(loadImage(*vfs_, "textures/t/absent.tga"));
    try {
        loadImage(*vfs_, "textures/t/broken");
        FAIL() << "malformed image accepted";
    } catch (const ImageError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("textures/t/broken.tga"), std::string::npos) << message;
        EXPECT_NE(message.find("pak0.pk3"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace q3
