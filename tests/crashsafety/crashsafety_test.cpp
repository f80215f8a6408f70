// Kills a process that is overwriting a file with SIGKILL at random moments (fixed seed) and checks
// that the file always holds either its old or its new bytes, and that removeStaleTemporaries
// clears every temporary the killed process left behind.
//
// A scenario names a command that overwrites one target file: the helper crash_bsp_writer
// (q3::bsp::writeBsp of a 12 MB BSP in a loop), and the lighting stage (`q3map2 -light -fast -sh`
// relighting a small map in place). Further commands are further entries of crashScenarios().
#include "bspfile.h"
#include "file_io.h"
#include "synthetic_bsp.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <functional>
#include <random>
#include <spawn.h>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct CrashScenario {
    std::string name;
    // Writes the target with its old content into `dir`; returns the target's path.
    std::function<fs::path(const fs::path& dir)> prepare;
    // The command overwriting `target`. With `loop` it should keep writing until killed when it
    // can, so that kills land inside writes rather than after the process ended.
    std::function<std::vector<std::string>(const fs::path& target, bool loop)> command;
    // True when the command spends most of its time writing, so that some of the kills must find
    // temporaries; a compiler stage mostly computes and writes only at its end.
    bool mostlyWriting = false;
};

std::vector<CrashScenario> crashScenarios() {
    constexpr uint32_t kOldSeed = 1, kNewSeed = 2;
    return {
        CrashScenario{
            "bsp_writer",
            [](const fs::path& dir) {
                const fs::path target = dir / "maps" / "crash.bsp";
                fs::create_directories(target.parent_path());
                std::vector<std::string> args = {CRASH_BSP_WRITER, target.string(), std::to_string(kOldSeed), "1"};
                std::string line;
                for (const std::string& a : args) line += "'" + a + "' ";
                if (q3::test::runCommand(line) != 0) throw std::runtime_error("cannot write the old BSP");
                return target;
            },
            [](const fs::path& target, bool loop) {
                return std::vector<std::string>{CRASH_BSP_WRITER, target.string(), std::to_string(kNewSeed),
                                                loop ? "0" : "1"};
            },
            true,
        },
        CrashScenario{
            "light_sh",
            [](const fs::path& dir) {
                const fs::path target = dir / "maps" / "room.bsp";
                fs::create_directories(target.parent_path());
                q3::writeFileAtomic(target, q3::bsp::serializeBsp(q3::bsp::test::makeSyntheticBsp()));
                return target;
            },
            [](const fs::path& target, bool) {
                return std::vector<std::string>{q3::test::q3map2Exe().string(), "-fs_basepath",
                                                q3::test::openArenaBase().string(), "-fs_game", "baseoa", "-light",
                                                "-fast", "-sh", target.string()};
            },
            false,
        },
    };
}

// Starts `argv` with its output discarded; returns the child's pid.
pid_t spawn(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + argv[0]);
    return pid;
}

int waitFor(pid_t pid) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) throw std::runtime_error("waitpid failed");
    }
    return status;
}

std::vector<fs::path> temporariesOf(const fs::path& target) {
    std::vector<fs::path> out;
    const std::string prefix = q3::atomicTempPrefix(target);
    for (const auto& item : fs::directory_iterator(target.parent_path()))
        if (item.path().filename().string().rfind(prefix, 0) == 0) out.push_back(item.path());
    return out;
}

// What repeated kills left behind.
struct KillOutcome {
    int keptOld = 0;            // the target still held the old bytes
    int gotNew = 0;             // it held the new bytes
    int torn = 0;               // it held anything else
    int withLeftovers = 0;      // temporaries were left beside it
    int badCleanups = 0;        // removeStaleTemporaries miscounted or left some
};

// Runs `scenario` to completion once (its output is the new content), then `kills` times: restores
// the old content, starts the command and kills it after a random delay (fixed seed) spread over
// three complete runs, so kills land both before the first rename and inside later writes.
KillOutcome killRepeatedly(const CrashScenario& scenario, int kills, const fs::path& dir) {
    const fs::path target = scenario.prepare(dir);
    const std::vector<uint8_t> oldBytes = q3::readFileBytes(target);

    const auto start = Clock::now();
    const int status = waitFor(spawn(scenario.command(target, false)));
    const auto fullRun = Clock::now() - start;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error(scenario.name + " failed on its own");
    const std::vector<uint8_t> newBytes = q3::readFileBytes(target);
    if (oldBytes == newBytes) throw std::runtime_error(scenario.name + " did not change the file");
    if (!temporariesOf(target).empty()) throw std::runtime_error(scenario.name + ": a completed write left a temporary");

    std::mt19937 random(20261121);
    const auto fullRunUs = std::chrono::duration_cast<std::chrono::microseconds>(fullRun).count();
    // Three runs' worth rather than two leaves room for a machine that slows down under load.
    std::uniform_int_distribution<long long> delayUs(0, 3 * std::max<long long>(fullRunUs, 1000));
    KillOutcome outcome;
    for (int kill = 0; kill < kills; ++kill) {
        q3::writeFileAtomic(target, oldBytes);
        const pid_t pid = spawn(scenario.command(target, true));
        std::this_thread::sleep_for(std::chrono::microseconds(delayUs(random)));
        ::kill(pid, SIGKILL);
        waitFor(pid);

        const std::vector<uint8_t> now = q3::readFileBytes(target);
        if (now == oldBytes) ++outcome.keptOld;
        else if (now == newBytes) ++outcome.gotNew;
        else ++outcome.torn;

        const std::vector<fs::path> leftovers = temporariesOf(target);
        outcome.withLeftovers += !leftovers.empty();
        if (q3::removeStaleTemporaries(target) != int(leftovers.size()) || !temporariesOf(target).empty())
            ++outcome.badCleanups;
    }
    std::printf("%s: %d kills: %d kept the old file, %d had the new one, %d torn, %d left temporaries\n",
                scenario.name.c_str(), kills, outcome.keptOld, outcome.gotNew, outcome.torn, outcome.withLeftovers);
    return outcome;
}

class CrashSafety : public ::testing::TestWithParam<CrashScenario> {};

TEST_P(CrashSafety, KilledWriterLeavesOldOrNewFileAndRemovableTemporaries) {
    const KillOutcome outcome = killRepeatedly(GetParam(), 50, q3::test::tempDir());
    EXPECT_EQ(outcome.torn, 0) << "a kill left a file that is neither the old nor the new content";
    EXPECT_EQ(outcome.badCleanups, 0) << "removeStaleTemporaries did not remove exactly the leftovers";
    // Some kills must have interrupted a write in progress, or the test did not exercise its case.
    if (GetParam().mostlyWriting) {
        EXPECT_GT(outcome.withLeftovers, 0) << "no kill interrupted a write; the delays do not cover the writes";
    }
    // Both outcomes must occur, or the delays do not span the command's run.
    EXPECT_GT(outcome.keptOld, 0);
    EXPECT_GT(outcome.gotNew, 0);
}

INSTANTIATE_TEST_SUITE_P(Commands, CrashSafety, ::testing::ValuesIn(crashScenarios()),
                         [](const ::testing::TestParamInfo<CrashScenario>& info) { return info.param.name; });

// Negative control: the same kills against a writer that rewrites the target in place must tear it,
// so a passing scenario above means something.
TEST(CrashSafetyControl, InPlaceWriterIsCaught) {
    CrashScenario direct = crashScenarios().front();
    direct.name = "in_place_writer";
    const auto atomicCommand = direct.command;
    direct.command = [atomicCommand](const fs::path& target, bool loop) {
        std::vector<std::string> argv = atomicCommand(target, loop);
        argv.push_back("direct");
        return argv;
    };
    const KillOutcome outcome = killRepeatedly(direct, 20, q3::test::tempDir());
    EXPECT_GT(outcome.torn, 0) << "killing an in-place writer never tore the file: the kill timing is off";
}

// The file the helper writes is a valid BSP, so the scenario checks a real writeBsp output.
TEST(CrashSafetyHelper, WritesAValidBsp) {
    const fs::path dir = q3::test::tempDir();
    const fs::path target = dir / "valid.bsp";
    const std::string line = std::string("'") + CRASH_BSP_WRITER + "' '" + target.string() + "' 7 2";
    ASSERT_EQ(q3::test::runCommand(line), 0);
    const q3::bsp::Bsp read = q3::bsp::readBsp(target);
    EXPECT_EQ(read.lightmaps.size(), 160u * q3::bsp::kLightmapPageBytes);
    EXPECT_EQ(read.drawVerts.size(), 100000u);
    EXPECT_TRUE(temporariesOf(target).empty());
}

}  // namespace
