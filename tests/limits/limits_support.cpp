#include "limits_support.h"

#include "bspfile.h"
#include "file_io.h"
#include "synthetic_bsp.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>

namespace q3::test {
namespace fs = std::filesystem;

long limitsRssBoundMb() {
#if defined(__SANITIZE_ADDRESS__)
    return 3072;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    return 3072;
#endif
#endif
    return 1024;
}

namespace {

bsp::Bsp roomWithKeys(const std::string& worldspawnKeys) {
    bsp::Bsp room = bsp::test::makeSyntheticBsp();
    const std::string anchor = "\"classname\" \"worldspawn\"\n";
    const size_t at = room.entities.find(anchor);
    if (at == std::string::npos) throw std::runtime_error("synthetic BSP has no worldspawn");
    room.entities.insert(at + anchor.size(), worldspawnKeys);
    return room;
}

}  // namespace

fs::path writeRoom(const fs::path& game, const std::string& worldspawnKeys) {
    return writeMapFile(game, "room.bsp", bsp::serializeBsp(roomWithKeys(worldspawnKeys)));
}

fs::path writeWideRoom(const fs::path& game, float halfExtent, const std::string& worldspawnKeys) {
    bsp::Bsp room = roomWithKeys(worldspawnKeys);
    for (int axis = 0; axis < 3; ++axis) {
        room.models.at(0).mins[axis] = -halfExtent;
        room.models.at(0).maxs[axis] = halfExtent;
    }
    return writeMapFile(game, "wide.bsp", bsp::serializeBsp(room));
}

fs::path writeMapFile(const fs::path& game, const std::string& name, const std::vector<uint8_t>& bytes) {
    const fs::path path = game / "baseoa" / "maps" / name;
    fs::create_directories(path.parent_path());
    writeFileAtomic(path, bytes);
    return path;
}

std::vector<std::string> q3map2Command(const fs::path& game, const std::vector<std::string>& common,
                                       const std::vector<std::string>& stage, const fs::path& bsp) {
    std::vector<std::string> argv = {q3map2Exe().string()};
    argv.insert(argv.end(), common.begin(), common.end());
    argv.insert(argv.end(), {"-fs_basepath", game.string(), "-fs_game", "baseoa"});
    argv.insert(argv.end(), stage.begin(), stage.end());
    argv.push_back(bsp.string());
    return argv;
}

MeasuredRun runQ3map2(const std::vector<std::string>& argv, double seconds) {
    RunLimits limits;
    limits.seconds = seconds;
    const MeasuredRun run = runMeasured(argv, limits);
    std::string line;
    for (const std::string& a : argv) line += a + " ";
    std::printf("%.2f s, %ld MB peak: %s\n", run.seconds, run.peakRssKb / 1024, line.c_str());
    return run;
}

void expectBounded(const MeasuredRun& run, long rssBoundMb) {
    if (rssBoundMb <= 0) rssBoundMb = limitsRssBoundMb();
    EXPECT_FALSE(run.signalled) << run.describe();
    EXPECT_FALSE(run.timedOut) << run.describe();
    EXPECT_LT(run.peakRssKb / 1024, rssBoundMb) << run.describe();
    EXPECT_EQ(run.output.find("bad_alloc"), std::string::npos) << run.describe();
    EXPECT_EQ(run.output.find("terminate called"), std::string::npos) << run.describe();
}

void expectOneLineError(const MeasuredRun& run, int exitCode, const std::string& needle) {
    expectBounded(run);
    EXPECT_EQ(run.exitCode, exitCode) << run.describe();
    const std::vector<std::string> errors = run.linesStartingWith("ERROR:");
    ASSERT_EQ(errors.size(), 1u) << run.describe();
    EXPECT_NE(errors[0].find(needle), std::string::npos) << "'" << needle << "' not in: " << errors[0];
}

void expectSuccess(const MeasuredRun& run, const std::string& needle, long rssBoundMb) {
    expectBounded(run, rssBoundMb);
    EXPECT_EQ(run.exitCode, 0) << run.describe();
    EXPECT_TRUE(run.linesStartingWith("ERROR:").empty()) << run.describe();
    if (!needle.empty()) {
        EXPECT_NE(run.output.find(needle), std::string::npos) << "'" << needle << "' not in:\n" << run.describe();
    }
}

}  // namespace q3::test
