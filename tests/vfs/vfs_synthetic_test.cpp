// Search order, overrides and error handling on small game trees built by the test.
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "test_data.h"
#include "vfs.h"
#include "zip_builder.h"

namespace q3 {
namespace {

namespace fs = std::filesystem;
using test::writeLoose;
using test::writeZip;

std::string text(const std::optional<std::vector<uint8_t>>& bytes) {
    return bytes ? std::string(bytes->begin(), bytes->end()) : std::string("<missing>");
}

struct Captured {
    Log log{false};
    std::vector<std::string> warnings;
    Captured() {
        log.addSink([this](LogLevel level, std::string_view message) {
            if (level == LogLevel::Warning) warnings.emplace_back(message);
        });
    }
};

VfsOptions optionsFor(const fs::path& base) {
    VfsOptions options;
    options.basePaths = {base};
    return options;
}

TEST(VfsOrder, LaterPk3NamesWinAndLooseFilesWinOverPk3s) {
    const fs::path base = test::tempDir();
    writeZip(base / "baseq3/pak0.pk3", {{"textures/a.txt", "pak0"}, {"only0.txt", "zero"}, {"shared.txt", "pak0"}});
    writeZip(base / "baseq3/pak1.pk3", {{"textures/a.txt", "pak1"}, {"shared.txt", "pak1"}});
    writeZip(base / "baseq3/Zzz.PK3", {{"textures/a.txt", "zzz"}});
    writeLoose(base / "baseq3/shared.txt", "loose");
    Captured capture;
    Vfs vfs(optionsFor(base), capture.log);

    EXPECT_EQ(text(vfs.read("textures/a.txt")), "zzz");
    EXPECT_EQ(text(vfs.read("only0.txt")), "zero");
    EXPECT_EQ(text(vfs.read("shared.txt")), "loose");
    EXPECT_FALSE(vfs.read("nothing.txt"));
    EXPECT_FALSE(vfs.exists("nothing.txt"));
    EXPECT_TRUE(vfs.exists("only0.txt"));
    ASSERT_EQ(vfs.sources().size(), 4u);
    EXPECT_EQ(vfs.sources()[0].kind, VfsSource::Kind::Folder);
    EXPECT_EQ(vfs.sources()[1].location.filename(), "Zzz.PK3");
    EXPECT_EQ(vfs.sources()[2].location.filename(), "pak1.pk3");
    EXPECT_EQ(vfs.sources()[3].location.filename(), "pak0.pk3");
    EXPECT_EQ(*vfs.sourceOf("textures/a.txt"), (base / "baseq3/Zzz.PK3").string() + ":textures/a.txt");
    EXPECT_EQ(*vfs.sourceOf("shared.txt"), (base / "baseq3/shared.txt").string());
    EXPECT_TRUE(capture.warnings.empty());

    // Every copy, lowest priority first.
    auto all = vfs.readAll("SHARED.txt");
    ASSERT_EQ(all.size(), 3u);
    EXPECT_EQ(std::string(all[0].begin(), all[0].end()), "pak0");
    EXPECT_EQ(std::string(all[1].begin(), all[1].end()), "pak1");
    EXPECT_EQ(std::string(all[2].begin(), all[2].end()), "loose");
}

TEST(VfsOrder, Pk3dirFoldersTakeTheirPlaceInNameOrder) {
    const fs::path base = test::tempDir();
    writeZip(base / "baseq3/pak0.pk3", {{"a.txt", "pak0"}, {"b.txt", "pak0"}, {"c.txt", "pak0"}});
    writeLoose(base / "baseq3/pak0b.pk3dir/a.txt", "pak0b dir");
    writeLoose(base / "baseq3/pak0b.pk3dir/B.TXT", "pak0b dir");
    writeZip(base / "baseq3/pak1.pk3", {{"a.txt", "pak1"}});
    Captured capture;
    Vfs vfs(optionsFor(base), capture.log);
    EXPECT_EQ(text(vfs.read("a.txt")), "pak1");
    EXPECT_EQ(text(vfs.read("b.txt")), "pak0b dir");
    EXPECT_EQ(text(vfs.read("c.txt")), "pak0");
    EXPECT_EQ(vfs.list("", "txt"), (std::vector<std::string>{"a.txt", "B.TXT", "c.txt"}));
}

TEST(VfsOrder, ModOverBaseAndHomeOverBase) {
    const fs::path base = test::tempDir() / "base";
    const fs::path home = base.parent_path() / "home";
    writeZip(base / "baseq3/pak0.pk3", {{"a.txt", "base pk3"}, {"b.txt", "base pk3"}, {"c.txt", "base pk3"},
                                        {"d.txt", "base pk3"}});
    writeLoose(base / "baseq3/e.txt", "base loose");
    writeZip(home / "baseq3/zz.pk3", {{"b.txt", "home pk3"}, {"e.txt", "home pk3"}});
    writeZip(base / "mymod/pak0.pk3", {{"c.txt", "mod pk3"}, {"b.txt", "mod pk3"}});
    writeLoose(home / "mymod/d.txt", "home mod loose");

    VfsOptions options = optionsFor(base);
    options.homePath = home;
    options.gameDirs = {"mymod"};
    Captured capture;
    Vfs vfs(options, capture.log);
    EXPECT_EQ(text(vfs.read("a.txt")), "base pk3");
    EXPECT_EQ(text(vfs.read("b.txt")), "mod pk3");         // mod beats home in the base game
    EXPECT_EQ(text(vfs.read("c.txt")), "mod pk3");
    EXPECT_EQ(text(vfs.read("d.txt")), "home mod loose");
    EXPECT_EQ(text(vfs.read("e.txt")), "home pk3");        // home pk3 beats base loose
    // Highest priority first: home/mymod, base/mymod(+pk3), home/baseq3(+pk3), base/baseq3(+pk3).
    ASSERT_EQ(vfs.sources().size(), 7u);
    EXPECT_EQ(vfs.sources()[0].location, home / "mymod");
    EXPECT_EQ(vfs.sources()[0].gameDir, "mymod");
    EXPECT_EQ(vfs.sources()[6].location, base / "baseq3/pak0.pk3");
}

TEST(VfsOrder, FirstBasePathWinsAndBaseGameCanBeOverridden) {
    const fs::path root = test::tempDir();
    writeLoose(root / "one/baseoa/x.txt", "one");
    writeLoose(root / "two/baseoa/x.txt", "two");
    writeLoose(root / "two/baseoa/y.txt", "two");
    writeLoose(root / "one/baseq3/x.txt", "q3");
    VfsOptions options;
    options.basePaths = {root / "one", root / "two"};
    options.baseGame = "baseoa";
    Captured capture;
    Vfs vfs(options, capture.log);
    EXPECT_EQ(text(vfs.read("x.txt")), "one");
    EXPECT_EQ(text(vfs.read("y.txt")), "two");
    EXPECT_EQ(vfs.basePaths().size(), 2u);

    // The same folder given twice (or as the home path) is searched once.
    options.basePaths = {root / "two", root / "two/"};
    options.homePath = root / "two";
    Vfs repeated(options, capture.log);
    EXPECT_EQ(repeated.sources().size(), 1u);
    EXPECT_EQ(repeated.readAll("x.txt").size(), 1u);
}

TEST(VfsLookup, CaseInsensitiveInArchivesAndFolders) {
    const fs::path base = test::tempDir();
    writeZip(base / "baseq3/pak0.pk3", {{"Textures/Base_Wall/Metal.TGA", "metal"}, {"scripts/", ""}});
    writeLoose(base / "baseq3/Scripts/Common.Shader", "loose shader");
    Captured capture;
    Vfs vfs(optionsFor(base), capture.log);
    EXPECT_EQ(text(vfs.read("textures/base_wall/metal.tga")), "metal");
    EXPECT_EQ(text(vfs.read("TEXTURES\\BASE_WALL\\METAL.tga")), "metal");
    EXPECT_EQ(text(vfs.read("scripts/common.shader")), "loose shader");
    EXPECT_FALSE(vfs.exists("scripts"));       // folders are not files
    EXPECT_FALSE(vfs.exists("../baseq3/pak0.pk3"));  // nothing escapes the game folder
}

// Folders are listed once and their entries kept: a name's spellings resolve as on disk, the
// lower-case one first, then the smallest, whichever is looked up first.
TEST(VfsLookup, CaseVariantsTakeTheLowerCaseOrElseTheSmallestSpelling) {
    const fs::path base = test::tempDir();
    writeLoose(base / "baseq3/Scripts/x.shader", "upper");
    writeLoose(base / "baseq3/scripts/x.shader", "lower");
    writeLoose(base / "baseq3/Models/m.txt", "mixed");
    writeLoose(base / "baseq3/MODELS/m.txt", "capitals");
    writeLoose(base / "baseq3/models2/Skin.TGA", "skin");
    Captured capture;
    Vfs vfs(optionsFor(base), capture.log);
    for (int pass = 0; pass < 2; ++pass) {
        EXPECT_EQ(text(vfs.read("SCRIPTS/X.shader")), "lower");
        EXPECT_EQ(text(vfs.read("models/m.txt")), "capitals");
        EXPECT_EQ(text(vfs.read("models2/skin.tga")), "skin");
        EXPECT_FALSE(vfs.exists("models3/skin.tga"));
    }
    EXPECT_EQ(vfs.sourceOf("models/M.TXT"), (base / "baseq3/MODELS/m.txt").string());
}

TEST(VfsList, UnionOverSourcesEachOnceSorted) {
    const fs::path base = test::tempDir();
    writeZip(base / "baseq3/pak0.pk3",
             {{"scripts/base.shader", "0"}, {"scripts/Sky.shader", "0"}, {"scripts/readme.txt", ""},
              {"scripts/sub/deep.shader", ""}, {"other/x.shader", ""}});
    writeZip(base / "baseq3/pak1.pk3", {{"scripts/sky.shader", "1"}, {"scripts/custom.SHADER", "1"}});
    writeLoose(base / "baseq3/scripts/loose.shader", "");
    writeLoose(base / "mod/Scripts/modded.shader", "");
    VfsOptions options = optionsFor(base);
    options.gameDirs = {"mod"};
    Captured capture;
    Vfs vfs(options, capture.log);
    EXPECT_EQ(vfs.list("scripts", "shader"),
              (std::vector<std::string>{"scripts/base.shader", "scripts/custom.SHADER", "scripts/loose.shader",
                                        "Scripts/modded.shader", "scripts/sky.shader"}));
    EXPECT_EQ(vfs.list("scripts/", ".shader"), vfs.list("SCRIPTS", "SHADER"));
    EXPECT_EQ(vfs.list("scripts", "").size(), 6u);  // plus readme.txt
    EXPECT_EQ(vfs.list("scripts/sub", "shader"), (std::vector<std::string>{"scripts/sub/deep.shader"}));
    EXPECT_TRUE(vfs.list("missing", "shader").empty());
}

TEST(VfsErrors, CorruptPk3IsSkippedWithAWarningNamingIt) {
    const fs::path base = test::tempDir();
    writeZip(base / "baseq3/pak0.pk3", {{"a.txt", "good"}});
    writeLoose(base / "baseq3/pak1.pk3", "this is not a zip archive at all");
    // A real archive cut in half loses its central directory.
    writeZip(base / "whole.zip", {{"a.txt", std::string(5000, 'x')}, {"b.txt", "b"}});
    std::ifstream in(base / "whole.zip", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    writeLoose(base / "baseq3/pak2.pk3", bytes.substr(0, bytes.size() / 2));

    Captured capture;
    Vfs vfs(optionsFor(base), capture.log);
    EXPECT_EQ(text(vfs.read("a.txt")), "good");
    EXPECT_FALSE(vfs.exists("b.txt"));
    ASSERT_EQ(capture.warnings.size(), 2u);
    EXPECT_NE(capture.warnings[0].find("pak2.pk3"), std::string::npos) << capture.warnings[0];
    EXPECT_NE(capture.warnings[1].find("pak1.pk3"), std::string::npos) << capture.warnings[1];
    EXPECT_NE(capture.warnings[1].find("skipped"), std::string::npos);
    EXPECT_EQ(capture.log.warningCount(), 2);
}

TEST(VfsErrors, DamagedEntryDataIsAnErrorNamingArchiveAndEntry) {
    const fs::path base = test::tempDir();
    std::string payload;
    uint32_t state = 12345;  // incompressible bytes, so the damage lands inside the entry's data
    for (int i = 0; i < 20000; ++i) {
        state = state * 1664525u + 1013904223u;
        payload += char(state >> 24);
    }
    writeZip(base / "baseq3/pak0.pk3", {{"textures/big.txt", payload}});
    // Corrupt the compressed bytes but keep the central directory intact.
    std::fstream file(base / "baseq3/pak0.pk3", std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(200);
    const std::string garbage(400, '\x5A');
    file.write(garbage.data(), std::streamsize(garbage.size()));
    file.close();

    Captured capture;
    Vfs vfs(optionsFor(base), capture.log);
    ASSERT_TRUE(vfs.exists("textures/big.txt"));
    try {
        vfs.read("textures/big.txt");
        FAIL() << "damaged data was accepted";
    } catch (const FileError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("pak0.pk3"), std::string::npos) << message;
        EXPECT_NE(message.find("textures/big.txt"), std::string::npos) << message;
    }
}

TEST(VfsThreads, ConcurrentReadsSeeTheSameBytes) {
    const fs::path base = test::tempDir();
    test::ZipFiles files;
    for (int i = 0; i < 40; ++i) files.emplace_back("data/f" + std::to_string(i) + ".txt", std::string(100 + i * 37, char('a' + i % 26)));
    writeZip(base / "baseq3/pak0.pk3", files);
    writeLoose(base / "baseq3/data/f3.txt", "loose three");
    Captured capture;
    const Vfs vfs(optionsFor(base), capture.log);
    std::vector<int> mismatches(4, 0);
    std::vector<std::thread> workers;
    for (int t = 0; t < 4; ++t)
        workers.emplace_back([&, t] {
            for (int round = 0; round < 25; ++round)
                for (int i = 0; i < 40; ++i) {
                    const std::string expected = i == 3 ? "loose three" : files[i].second;
                    if (text(vfs.read("data/F" + std::to_string(i) + ".TXT")) != expected) ++mismatches[t];
                }
        });
    for (auto& worker : workers) worker.join();
    EXPECT_EQ(mismatches, std::vector<int>(4, 0));
}

TEST(VfsErrors, UnknownGameProfile) {
    VfsOptions options;
    options.game = "doom3";
    Captured capture;
    try {
        Vfs vfs(options, capture.log);
        FAIL() << "unknown game accepted";
    } catch (const FileError& error) {
        EXPECT_NE(std::string(error.what()).find("doom3"), std::string::npos);
    }
}

TEST(VfsDetection, BasePathAndGameFolderFromTheMapPath) {
    const fs::path root = test::tempDir();
    writeZip(root / "baseoa/pak0.pk3", {{"scripts/oa.shader", "oa"}});
    writeLoose(root / "baseq3/scripts/q3.shader", "q3");
    VfsOptions options;
    options.mapPath = root / "baseoa/maps/test.bsp";
    Captured capture;
    Vfs vfs(options, capture.log);
    ASSERT_EQ(vfs.basePaths().size(), 1u);
    EXPECT_EQ(vfs.basePaths()[0], root.lexically_normal());
    // baseoa becomes a mod folder above baseq3.
    EXPECT_EQ(text(vfs.read("scripts/oa.shader")), "oa");
    EXPECT_EQ(text(vfs.read("scripts/q3.shader")), "q3");
    EXPECT_EQ(vfs.sources()[0].gameDir, "baseoa");

    // An explicit base path disables detection.
    options.basePaths = {root / "nowhere"};
    Vfs explicitVfs(options, capture.log);
    EXPECT_FALSE(explicitVfs.exists("scripts/oa.shader"));
}

}  // namespace
}  // namespace q3
