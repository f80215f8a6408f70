// Every shipped OpenArena BSP loads, validates, and writes back with byte-identical lump payloads;
// mutations of a real map are refused with the right message.
#include "synthetic_bsp.h"

#include "file_io.h"
#include "sh_grid_lump.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace q3::bsp::test {
namespace {

TEST(RealBsp, EveryMapLoadsValidatesAndRoundTrips) {
    const std::vector<std::filesystem::path> maps = q3::test::allRealBsps();
    int checked = 0;
    int withEntries[2] = {0, 0};  // 17- and 18-entry headers seen
    for (const std::filesystem::path& path : maps) {
        SCOPED_TRACE(path.string());
        const std::vector<uint8_t> original = readFileBytes(path);
        Bsp bsp;
        ASSERT_NO_THROW(bsp = parseBsp(original, path.string())) << path;
        ASSERT_EQ(bsp.version, kVersionQ3);
        ASSERT_TRUE(bsp.headerLumps == 17 || bsp.headerLumps == 18) << bsp.headerLumps;
        ++withEntries[bsp.headerLumps - 17];
        EXPECT_FALSE(bsp.models.empty());
        EXPECT_FALSE(bsp.surfaces.empty());

        // Payloads as seen by an independent header reader.
        const std::vector<RawEntry> entries = rawEntries(original, bsp.headerLumps);
        for (int lump = 0; lump < kMaxLumps; ++lump) {
            const std::vector<uint8_t> expected =
                lump < bsp.headerLumps ? rawLump(original, entries[static_cast<size_t>(lump)]) : std::vector<uint8_t>{};
            ASSERT_EQ(lumpBytes(bsp, lump), expected) << "lump " << lumpName(lump);
        }

        // The written file carries the same payloads and is a fixed point of read + write.
        const std::vector<uint8_t> written = serializeBsp(bsp);
        const std::vector<RawEntry> writtenEntries = rawEntries(written, bsp.headerLumps);
        for (int lump = 0; lump < bsp.headerLumps; ++lump)
            ASSERT_EQ(rawLump(written, writtenEntries[static_cast<size_t>(lump)]),
                      rawLump(original, entries[static_cast<size_t>(lump)]))
                << "lump " << lumpName(lump);
        const Bsp reread = parseBsp(written, path.string());
        EXPECT_EQ(reread.headerLumps, bsp.headerLumps);
        ASSERT_EQ(serializeBsp(reread), written) << "second write differs";

        // The entity lump parses and starts with worldspawn.
        std::vector<Entity> entities;
        ASSERT_NO_THROW(entities = parseEntities(bsp.entities, path.string()));
        ASSERT_FALSE(entities.empty());
        EXPECT_EQ(entities[0].classname(), "worldspawn");
        ++checked;
    }
    EXPECT_GE(checked, 100) << "real BSPs checked";
    EXPECT_GT(withEntries[0], 0) << "no 17-entry header seen";
    EXPECT_GT(withEntries[1], 0) << "no 18-entry (q3map2) header seen";
}

TEST(RealBsp, WriteToDiskAndAddShGrid) {
    const std::filesystem::path source = q3::test::realBsp("oacmpdm1");
    const Bsp bsp = readBsp(source);
    const std::filesystem::path out = q3::test::tempDir() / "oacmpdm1.bsp";
    writeBsp(out, bsp);
    const Bsp back = readBsp(out);
    for (int lump = 0; lump < kMaxLumps; ++lump) EXPECT_EQ(lumpBytes(back, lump), lumpBytes(bsp, lump));

    Bsp withSh = bsp;
    attachShGrid(withSh, makeShGridLump(4, 3, 2));
    writeBsp(out, withSh);
    const std::vector<uint8_t> image = readFileBytes(out);
    int32_t version;
    std::memcpy(&version, image.data() + 4, 4);
    EXPECT_EQ(version, 47);
    const Bsp shBack = readBsp(out);
    EXPECT_EQ(shBack.headerLumps, 19);
    EXPECT_EQ(shBack.shGrid, withSh.shGrid);
    for (int lump = 0; lump < 17; ++lump) EXPECT_EQ(lumpBytes(shBack, lump), lumpBytes(bsp, lump));
}

class RealBspMutation : public ::testing::Test {
protected:
    void SetUp() override {
        path_ = q3::test::realBsp("oacmpdm1").string();
        original_ = readFileBytes(path_);
        bsp_ = parseBsp(original_, path_);
    }

    void expectError(const std::vector<uint8_t>& image, const std::string& fragment) {
        try {
            (void)parseBsp(image, path_);
            ADD_FAILURE() << "no error; expected \"" << fragment << "\"";
        } catch (const BspError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(path_ + ": ", 0), 0u) << message;
            EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message;
        }
    }
    void expectError(const Bsp& bsp, const std::string& fragment) { expectError(serializeBsp(bsp), fragment); }

    std::string path_;
    std::vector<uint8_t> original_;
    Bsp bsp_;
};

TEST_F(RealBspMutation, TruncatedFile) {
    std::vector<uint8_t> image = original_;
    image.resize(image.size() - 1000);
    expectError(image, "extends past the end of the file");
    image.resize(120);
    expectError(image, "header: truncated");
}

TEST_F(RealBspMutation, WrongVersion) {
    std::vector<uint8_t> image = original_;
    storeI32(image, 4, 45);
    expectError(image, "header: unsupported version 45");
}

TEST_F(RealBspMutation, LastSurfaceVertsOutOfRange) {
    Bsp bsp = bsp_;
    bsp.surfaces.back().firstVert = static_cast<int32_t>(bsp.drawVerts.size());
    bsp.surfaces.back().numVerts = 1;
    expectError(bsp, "surfaces: record " + std::to_string(bsp.surfaces.size() - 1) + ": vertex range");
}

TEST_F(RealBspMutation, NaNPlaneAndInfVertex) {
    Bsp bsp = bsp_;
    bsp.planes[10].dist = std::numeric_limits<float>::quiet_NaN();
    expectError(bsp, "planes: record 10: dist is not finite");
    bsp = bsp_;
    bsp.drawVerts[100].xyz[0] = std::numeric_limits<float>::infinity();
    expectError(bsp, "drawverts: record 100: xyz is not finite");
}

TEST_F(RealBspMutation, DanglingNodeChildAndLeafSurface) {
    Bsp bsp = bsp_;
    bsp.nodes[0].children[0] = static_cast<int32_t>(bsp.nodes.size());
    expectError(bsp, "nodes: record 0: child node");
    bsp = bsp_;
    bsp.leafSurfaces[0] = static_cast<int32_t>(bsp.surfaces.size());
    expectError(bsp, "leafsurfaces: record 0: surface");
}

TEST_F(RealBspMutation, SubmodelRangeAndShader) {
    Bsp bsp = bsp_;
    bsp.models.back().numSurfaces += static_cast<int32_t>(bsp.surfaces.size());
    expectError(bsp, "models: record " + std::to_string(bsp.models.size() - 1) + ": surface range");
    bsp = bsp_;
    bsp.brushSides[0].shaderNum = static_cast<int32_t>(bsp.shaders.size());
    expectError(bsp, "brushsides: record 0: shaderNum");
}

TEST_F(RealBspMutation, VisibilityHeader) {
    Bsp bsp = bsp_;
    ASSERT_GE(bsp.visibility.size(), 8u);
    int32_t clusters;
    std::memcpy(&clusters, bsp.visibility.data(), 4);
    clusters += 100;
    std::memcpy(bsp.visibility.data(), &clusters, 4);
    expectError(bsp, "visibility:");
}

TEST_F(RealBspMutation, UnterminatedEntityQuote) {
    std::string text = bsp_.entities;
    const size_t quote = text.rfind('"');
    ASSERT_NE(quote, std::string::npos);
    text.erase(quote, 1);
    try {
        (void)parseEntities(text, path_);
        ADD_FAILURE() << "expected an entity error";
    } catch (const BspError& e) {
        EXPECT_NE(std::string(e.what()).find(path_ + ": entities: line "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("unterminated quoted string"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace q3::bsp::test
