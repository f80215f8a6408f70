// The quick start of README.md and docs/user-guide.md: the same marked block in both, and running
// it (as a new user would, from a folder holding build/q3map2/q3map2) relights a real OpenArena map
// with the SH grid and leaves every output the block promises. Stdin is a pipe nobody writes to, so
// a command that waited for input would hang until the timeout and fail.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "doc_blocks.h"
#include "test_data.h"

namespace q3::test {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

QuickStartBlock onlyBlockOf(const std::string& relativePath) {
    const fs::path path = fs::path(Q3MAP_SOURCE_DIR) / relativePath;
    std::vector<QuickStartBlock> blocks = quickStartBlocks(readText(path), relativePath);
    EXPECT_EQ(blocks.size(), 1u) << relativePath << " should hold one quick-start block";
    return blocks.empty() ? QuickStartBlock{} : blocks.front();
}

int32_t readInt(const std::string& bytes, size_t offset) {
    int32_t value = 0;
    if (offset + 4 <= bytes.size()) std::memcpy(&value, bytes.data() + offset, 4);  // little-endian host
    return value;
}

// How many surfaces of a kind the .srf beside a BSP lists ("12 // ESurfaceType::Meta V: ...").
int srfSurfacesOfKind(const std::string& srf, const std::string& kind) {
    int count = 0;
    const std::string marker = "// ESurfaceType::" + kind + " ";
    for (size_t at = srf.find(marker); at != std::string::npos; at = srf.find(marker, at + 1)) ++count;
    return count;
}

TEST(DocsBlocks, FindsMarkedBlocksOnly) {
    const std::string text = "# Title\n```sh\nnot marked\n```\n"
                             "<!-- quick-start creates: a.bsp out/b.png -->\n```sh\n# comment\ncmd one  # why\n\n"
                             "cmd two\n```\ntext\n";
    std::vector<QuickStartBlock> blocks = quickStartBlocks(text, "doc.md");
    ASSERT_EQ(blocks.size(), 1u);
    EXPECT_EQ(blocks[0].line, 5);
    EXPECT_EQ(blocks[0].creates, (std::vector<std::string>{"a.bsp", "out/b.png"}));
    EXPECT_EQ(blocks[0].script, "# comment\ncmd one  # why\n\ncmd two\n");
    EXPECT_EQ(commandLines(blocks[0].script), (std::vector<std::string>{"cmd one  # why", "cmd two"}));
}

TEST(DocsBlocks, MalformedMarkersAreErrorsNamingTheLine) {
    auto errorOf = [](const std::string& text) {
        try {
            quickStartBlocks(text, "doc.md");
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("<no error>");
    };
    EXPECT_EQ(errorOf("x\n<!-- quick-start creates: a -->\ntext\n"),
              "doc.md:2: quick-start marker is not followed by a ```sh block");
    EXPECT_EQ(errorOf("<!-- quick-start creates: -->\n```sh\nx\n```\n"), "doc.md:1: quick-start marker lists no outputs");
    EXPECT_EQ(errorOf("<!-- quick-start creates: a\n```sh\nx\n```\n"),
              "doc.md:1: quick-start marker does not end with -->");
    EXPECT_EQ(errorOf("<!-- quick-start creates: a -->\n```sh\nx\n"), "doc.md:1: quick-start block is never closed");
}

TEST(DocsQuickStart, ReadmeAndUserGuideShowTheSameQuickStart) {
    QuickStartBlock readme = onlyBlockOf("README.md");
    QuickStartBlock guide = onlyBlockOf("docs/user-guide.md");
    EXPECT_EQ(readme.script, guide.script);
    EXPECT_EQ(readme.creates, guide.creates);
    // It compiles with meta surfaces, relights with the SH grid and then looks at the result.
    std::string script = readme.script;
    EXPECT_NE(script.find(" -bsp -meta "), std::string::npos);
    EXPECT_NE(script.find(" -light "), std::string::npos);
    EXPECT_NE(script.find(" -sh "), std::string::npos);
    EXPECT_NE(script.find(" -shprobe "), std::string::npos);
    EXPECT_NE(script.find(" -shimage "), std::string::npos);
}

TEST(DocsQuickStart, RelightsARealMapWithTheShGridAndLeavesWhatItPromises) {
    const fs::path cache = dataCache();
    QuickStartBlock block = onlyBlockOf("README.md");
    ASSERT_FALSE(block.script.empty());

    const fs::path dir = tempDir();
    fs::create_directories(dir / "build/q3map2");
    fs::create_symlink(q3map2Exe(), dir / "build/q3map2/q3map2");
    std::ofstream(dir / "quickstart.sh") << block.script;

    const fs::path shippedBsp = cache / "loose/z_oacmp-volume1-v3/maps/oacmpdm1.bsp";
    const std::string shippedBefore = readText(shippedBsp);

    std::string output;
    const std::string command = "cd " + shellQuote(dir) + " && mkfifo stdin.fifo && exec 3<>stdin.fifo && " +
                                "Q3MAP_DATA_CACHE=" + shellQuote(cache) +
                                " timeout -s KILL 1200 sh -e -x quickstart.sh <&3";
    int status = runCommand(command, &output);
    fs::remove(dir / "stdin.fifo");  // nothing later should open it and block
    ASSERT_EQ(status, 0) << output;

    for (const std::string& file : block.creates) {
        ASSERT_TRUE(fs::exists(dir / file)) << file << " promised but not created\n" << output;
        EXPECT_GT(fs::file_size(dir / file), 0u) << file;
        const std::string bytes = readText(dir / file);
        if (fs::path(file).extension() == ".png") {
            EXPECT_EQ(bytes.substr(0, 8), "\x89PNG\r\n\x1a\n") << file;
        } else if (fs::path(file).extension() == ".bsp") {
            EXPECT_EQ(bytes.substr(0, 4), "IBSP") << file;
            EXPECT_EQ(readInt(bytes, 4), 47) << file << ": -sh makes a version 47 BSP";
            EXPECT_GT(readInt(bytes, 8 + 18 * 8 + 4), 0) << file << ": lump 18 (the SH grid) is empty";
            // -bsp -meta merged the brush faces into meta surfaces (plain -bsp leaves none); the
            // few faces left are the ones meta never takes (autosprite shaders).
            const fs::path srfPath = (dir / file).replace_extension(".srf");
            ASSERT_TRUE(fs::exists(srfPath)) << srfPath;
            const std::string srf = readText(srfPath);
            const int meta = srfSurfacesOfKind(srf, "Meta"), faces = srfSurfacesOfKind(srf, "Face");
            EXPECT_GT(meta, 1000) << srfPath << ": too few meta surfaces for a -bsp -meta compile";
            EXPECT_LT(faces * 100, meta) << srfPath << ": brush faces left out of meta surfaces";
        }
    }
    // Piped output gets q3map2's pacifier, and the run ends with each phase's time.
    EXPECT_NE(output.find("0...1...2...3...4...5...6...7...8...9...10 ("), std::string::npos) << output;
    for (const char* phase : {"seconds  load", "seconds  lightmaps", "seconds  SH grid", "seconds elapsed"})
        EXPECT_NE(output.find(phase), std::string::npos) << phase;
    EXPECT_NE(output.find("IBSP version 47"), std::string::npos);            // -info
    EXPECT_NE(output.find("grid from lump 18"), std::string::npos);          // -shprobe
    EXPECT_EQ(output.find("ERROR"), std::string::npos) << output;
    // The quick start copies the map; the shipped one is left alone.
    EXPECT_TRUE(readText(shippedBsp) == shippedBefore) << shippedBsp << " was modified";
}

}  // namespace
}  // namespace q3::test
