// q3map2 -shcubemap on a synthetic cubemap written by the test: the printed coefficients match the
// library projection of the same faces, the face order is +X -X +Y -Y +Z -Z, and bad faces give one
// clear error line naming the file.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "file_io.h"
#include "image.h"
#include "sh_cubemap.h"
#include "sh_tools.h"
#include "test_data.h"

namespace q3::shtools {
namespace {

Image solidImage(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
    Image image;
    image.width = width;
    image.height = height;
    for (int i = 0; i < width * height; ++i)
        for (uint8_t v : {r, g, b, uint8_t(255)}) image.rgba.push_back(v);
    return image;
}

// Six faces: grey 64 everywhere, the +Z face bright yellow, one red texel at the top left of +X.
std::array<std::string, 6> writeFaces(const std::filesystem::path& dir, int size) {
    std::array<std::string, 6> files;
    for (int f = 0; f < 6; ++f) {
        Image image = f == 4 ? solidImage(size, size, 255, 255, 0) : solidImage(size, size, 64, 64, 64);
        if (f == 0) image.rgba[0] = 255;
        files[size_t(f)] = (dir / ("face" + std::to_string(f) + (f % 2 ? ".png" : ".tga"))).string();
        writeFileAtomic(files[size_t(f)], f % 2 ? encodePng(image, false) : encodeTga(image, false));
    }
    return files;
}

// The nine "  <prefix>i r g b" lines of the output.
std::vector<std::array<double, 3>> parseCoefficients(const std::string& output, char prefix) {
    std::vector<std::array<double, 3>> out;
    std::istringstream in(output);
    std::string line;
    while (std::getline(in, line)) {
        const size_t at = line.find(std::string("  ") + prefix);
        if (at == std::string::npos || at + 3 >= line.size() || !std::isdigit(static_cast<unsigned char>(line[at + 3])))
            continue;
        std::array<double, 3> c{};
        int index = -1;
        if (std::sscanf(line.c_str() + at + 3, "%d %lf %lf %lf", &index, &c[0], &c[1], &c[2]) == 4 &&
            index == int(out.size()))
            out.push_back(c);
    }
    return out;
}

TEST(ShCubemapTool, PrintsTheProjectionOfTheFiles) {
    const std::filesystem::path dir = test::tempDir();
    for (int size : {3, 16}) {
        const std::array<std::string, 6> files = writeFaces(dir, size);
        std::string output;
        std::string command = test::q3map2Exe().string() + " -shcubemap -scale 255";
        for (const std::string& f : files) command += " " + f;
        ASSERT_EQ(test::runCommand(command, &output), 0) << output;
        const auto radiance = parseCoefficients(output, 'L');
        const auto irradiance = parseCoefficients(output, 'E');
        ASSERT_EQ(radiance.size(), 9u) << output;
        ASSERT_EQ(irradiance.size(), 9u) << output;

        const CubemapReport expected = projectCubemapFiles(files, 255);
        for (int i = 0; i < 9; ++i)
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_NEAR(radiance[size_t(i)][size_t(ch)], expected.radiance.c[i][ch], 1e-5);
                EXPECT_NEAR(irradiance[size_t(i)][size_t(ch)], expected.irradiance.c[i][ch], 1e-5);
            }
        // Closed form of coefficient 0 (mean radiance times 2 sqrt(pi)): blue is 64 on
        // five faces and 0 on +Z; green is 64 on five faces and 255 on +Z (each face a sixth of 4 pi).
        EXPECT_NEAR(radiance[0][2], 64.0 * 5 / 6 * sh::kUniformToCoeff0, 1e-4);
        EXPECT_NEAR(radiance[0][1], (64.0 * 5 + 255) / 6 * sh::kUniformToCoeff0, 1e-4);
        // Yellow above: towards +Z more red and green and less blue than towards -Z.
        const sh::SH9Color e = expected.irradiance;
        const sh::Rgb up = sh::evalIrradiance(e, {0, 0, 1}), down = sh::evalIrradiance(e, {0, 0, -1});
        EXPECT_GT(up.g, down.g + 100);
        EXPECT_LT(up.b, down.b - 100);
        EXPECT_NE(output.find("faces +X -X +Y -Y +Z -Z"), std::string::npos);
    }
}

TEST(ShCubemapTool, BadFacesGiveOneErrorNamingTheFile) {
    const std::filesystem::path dir = test::tempDir();
    std::array<std::string, 6> files = writeFaces(dir, 4);
    const std::string wide = (dir / "wide.png").string();
    writeFileAtomic(wide, encodePng(solidImage(8, 4, 1, 2, 3), false));
    const std::string smaller = (dir / "small.png").string();
    writeFileAtomic(smaller, encodePng(solidImage(2, 2, 1, 2, 3), false));
    const std::string garbage = (dir / "garbage.tga").string();
    writeFileAtomic(garbage, std::vector<uint8_t>{1, 2, 3});

    auto run = [&](const std::string& face3, std::string& output) {
        std::string command = test::q3map2Exe().string() + " -shcubemap";
        for (int f = 0; f < 6; ++f) command += " " + (f == 3 ? face3 : files[size_t(f)]);
        return test::runCommand(command, &output);
    };
    std::string output;
    EXPECT_EQ(run(wide, output), 1);
    EXPECT_NE(output.find("wide.png: face -Y is 8 x 4 texels, a cubemap face must be square"), std::string::npos)
        << output;
    EXPECT_EQ(run(smaller, output), 1);
    EXPECT_NE(output.find("small.png: face -Y is 2 texels wide"), std::string::npos) << output;
    EXPECT_EQ(run(garbage, output), 1);
    EXPECT_NE(output.find("garbage.tga"), std::string::npos) << output;
    EXPECT_EQ(run((dir / "missing.png").string(), output), 1);
    EXPECT_NE(output.find("missing.png"), std::string::npos) << output;
    // Too few faces and unknown options are usage errors (exit 2).
    EXPECT_EQ(test::runCommand(test::q3map2Exe().string() + " -shcubemap a.png b.png", &output), 2);
    EXPECT_EQ(test::runCommand(test::q3map2Exe().string() + " -shcubemap -bogus " + files[0] + " " + files[1] + " " +
                                   files[2] + " " + files[3] + " " + files[4] + " " + files[5],
                               &output),
              2);
    // The help text documents the face convention.
    ASSERT_EQ(test::runCommand(test::q3map2Exe().string() + " -help shcubemap", &output), 0);
    EXPECT_NE(output.find("+X right -Y down -Z"), std::string::npos) << output;
}

}  // namespace
}  // namespace q3::shtools
