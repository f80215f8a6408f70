// The q3map2 executable as scripts and CI jobs see it: exit codes 0/1/2 with the exact one-line
// error on stderr, -werror, the -stats file against docs/stats-schema.json, -help, and runs that
// never wait for input (stdin closed, or a pipe nobody writes to).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <rapidjson/document.h>
#include <rapidjson/schema.h>
#include <rapidjson/stringbuffer.h>
#include <sstream>
#include <string>

#include "tcp_listener.h"
#include "stats_schema.h"
#include "test_data.h"

namespace q3::test {
namespace {

namespace fs = std::filesystem;

std::string exe() { return shellQuote(q3map2Exe()); }

struct RunResult {
    int status = -1;
    std::string stdoutText;
    std::string stderrText;
};

// Each test works in one scratch folder (tempDir() empties the folder it returns, so it is asked
// once per test).
class CliExecutable : public ::testing::Test {
protected:
    const fs::path dir_ = tempDir();
    int runs_ = 0;

    // Runs `q3map2 <args>` through /bin/sh with stdin from /dev/null, keeping stdout and stderr
    // apart.
    RunResult runQ3map2(const std::string& args, const std::string& stdinRedirect = "</dev/null") {
        const fs::path out = dir_ / ("out" + std::to_string(runs_) + ".txt");
        const fs::path err = dir_ / ("err" + std::to_string(runs_++) + ".txt");
        RunResult run;
        // Grouped, so that the 2>&1 runCommand appends does not fold stderr back into stdout.
        run.status = runCommand("{ " + exe() + " " + args + " " + stdinRedirect + " >" + shellQuote(out) + " 2>" +
                                shellQuote(err) + "; }");
        auto slurp = [](const fs::path& p) {
            std::ifstream in(p);
            std::stringstream text;
            text << in.rdbuf();
            return text.str();
        };
        run.stdoutText = slurp(out);
        run.stderrText = slurp(err);
        return run;
    }

    void expectUsageError(const std::string& args, const std::string& message) {
        RunResult run = runQ3map2(args);
        EXPECT_EQ(run.status, 2) << args;
        EXPECT_EQ(run.stderrText, "ERROR: " + message + "\n") << args;
    }
};

std::string realMap() { return shellQuote(realBsp("oacmpdm1")); }


TEST_F(CliExecutable, SuccessIsExitZeroWithNothingOnStderr) {
    RunResult run = runQ3map2("-info " + realMap());
    EXPECT_EQ(run.status, 0);
    EXPECT_EQ(run.stderrText, "");
    EXPECT_NE(run.stdoutText.find("IBSP version 46"), std::string::npos) << run.stdoutText;
}

TEST_F(CliExecutable, UsageErrorsExitWithTwoAndOneLine) {
    expectUsageError("", "no stage given: expected a stage switch such as -light or -info before the map file "
                         "(see q3map2 -help)");
    expectUsageError("-ligt m.bsp", "unknown option '-ligt'; did you mean '-light'?");
    expectUsageError("-light -fats m.bsp", "unknown option '-fats'; did you mean '-fast'?");
    expectUsageError("-light -zzzzzzzzzzzz m.bsp", "unknown option '-zzzzzzzzzzzz' (see q3map2 -help light)");
    expectUsageError("-threads four -info m.bsp", "-threads: 'four' is not an integer (-threads <N>)");
    expectUsageError("-light -gridscalesh 0 m.bsp", "-gridscalesh: 0 is out of range (must be > 0)");
    expectUsageError("-light -gridsh 16 16 m.bsp", "-gridsh needs 3 values (-gridsh <X> <Y> <Z>)");
    expectUsageError("-light -samplesize", "-light needs a map file as its last argument (-light [options] "
                                           "<filename.map>)");
    expectUsageError("-light -v m.bsp", "common option -v must come before the stage switch -light");
    expectUsageError("-info m.txt", "map file 'm.txt' must end in .bsp, .map, .reg or .ent (or have no extension)");
    expectUsageError("-help ligth", "no help for unknown stage 'ligth'; did you mean 'light'?");
}

TEST_F(CliExecutable, WhatThisBuildLacksIsSaidExplicitly) {
    expectUsageError("-bsp -custinfoparms m.map", "-custinfoparms is a q3map2 option this build does not implement yet");
    expectUsageError("-analyze m.bsp", "-analyze is a q3map2 stage this build does not implement yet");
    expectUsageError("-light -fast -thresh 2 m.bsp", "-thresh is a q3map2 option this build does not implement yet");
    expectUsageError("-light -randomsamples m.bsp", "-randomsamples is a q3map2 option this build does not implement yet");
    expectUsageError("-fs_pakpath /p -info m.bsp", "-fs_pakpath is a q3map2 option this build does not implement yet");
    expectUsageError("-game sof2 -info m.bsp", "-game sof2 is a q3map2 game profile this build does not implement yet");
}

TEST_F(CliExecutable, CompileFailuresExitWithOne) {
    fs::path missing = dir_ / "missing.bsp";
    RunResult run = runQ3map2("-info " + shellQuote(missing));
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.stderrText, "ERROR: " + missing.string() + ": no such file\n");

    fs::path garbage = dir_ / "garbage.bsp";
    std::ofstream(garbage) << "this is not a BSP";
    run = runQ3map2("-light -fast " + shellQuote(garbage));
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.stderrText.rfind("ERROR: " + garbage.string(), 0), 0u) << run.stderrText;
    EXPECT_EQ(std::count(run.stderrText.begin(), run.stderrText.end(), '\n'), 1) << run.stderrText;
    std::ifstream back(garbage);
    std::string content;
    std::getline(back, content);
    EXPECT_EQ(content, "this is not a BSP");  // inputs are never modified
}

TEST_F(CliExecutable, HelpExitsWithZero) {
    RunResult run = runQ3map2("-help");
    EXPECT_EQ(run.status, 0);
    EXPECT_EQ(run.stdoutText.rfind("Usage: q3map2 [common options...] -STAGE [stage options...] MAPFILE\n", 0), 0u);
    EXPECT_NE(run.stdoutText.find("  -werror"), std::string::npos);
    EXPECT_NE(run.stdoutText.find("  -scale                    Scaling [not implemented yet]"), std::string::npos)
        << run.stdoutText;
    run = runQ3map2("-help light");
    EXPECT_EQ(run.status, 0);
    EXPECT_NE(run.stdoutText.find("  -gridscalesh <F>"), std::string::npos);
    EXPECT_NE(run.stdoutText.find("  -bounce <N>"), std::string::npos);
    EXPECT_EQ(run.stderrText, "");
}

TEST_F(CliExecutable, WerrorTurnsWarningsIntoFailure) {
    // A NetRadiant address nobody listens on gives exactly one warning, and nothing else does here.
    const std::string warned = "-connect 127.0.0.1:" + std::to_string(closedPort()) + " ";
    RunResult run = runQ3map2(warned + "-info " + realMap());
    EXPECT_EQ(run.status, 0) << run.stderrText;
    EXPECT_NE(run.stdoutText.find("WARNING: "), std::string::npos) << run.stdoutText;

    run = runQ3map2(warned + "-werror -info " + realMap());
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.stderrText, "ERROR: 1 warning(s) with -werror\n");

    run = runQ3map2("-werror -info " + realMap());  // no warning: -werror changes nothing
    EXPECT_EQ(run.status, 0) << run.stderrText;
}

TEST_F(CliExecutable, StatsFileFollowsTheSchemaAndCountsWarnings) {
    fs::path clean = dir_ / "clean.json", warned = dir_ / "warned.json";
    RunResult run = runQ3map2("-stats " + shellQuote(clean) + " -info " + realMap());
    ASSERT_EQ(run.status, 0) << run.stderrText;
    rapidjson::Document doc = test::readJsonFile(clean);
    EXPECT_EQ(statsSchemaViolation(doc), "");
    EXPECT_STREQ(doc["stage"].GetString(), "info");
    EXPECT_EQ(doc["warnings"].GetInt(), 0);
    EXPECT_GE(doc["threads"].GetInt(), 1);

    const std::string connect = "-connect 127.0.0.1:" + std::to_string(closedPort()) + " ";
    run = runQ3map2(connect + "-werror -threads 1 -stats " + shellQuote(warned) + " -info " + realMap());
    EXPECT_EQ(run.status, 1);  // the summary is still written for the CI job to read
    doc = test::readJsonFile(warned);
    EXPECT_EQ(statsSchemaViolation(doc), "");
    EXPECT_EQ(doc["warnings"].GetInt(), 1);
    EXPECT_EQ(doc["threads"].GetInt(), 1);
    EXPECT_EQ(std::string(doc["map"].GetString()), realBsp("oacmpdm1").string());
}

TEST_F(CliExecutable, NeverWaitsForInput) {
    // stdin closed altogether.
    RunResult run = runQ3map2("-info " + realMap(), "<&-");
    EXPECT_EQ(run.status, 0) << run.stderrText;
    // stdin a pipe that stays open and never delivers anything: reading it would block until the
    // timeout kills the process (exit 124).
    fs::path fifo = dir_ / "stdin.fifo";
    ASSERT_EQ(runCommand("mkfifo " + shellQuote(fifo)), 0);
    const std::string holdOpen = "exec 3<>" + shellQuote(fifo) + "; timeout -s KILL 120 ";
    int status = runCommand(holdOpen + exe() + " -info " + realMap() + " <&3 >/dev/null");
    EXPECT_EQ(status, 0);
    status = runCommand(holdOpen + exe() + " -light -nosuchoption m.bsp <&3 >/dev/null 2>&1");
    EXPECT_EQ(status, 2);
    fs::remove(fifo);  // nothing later should open it and block
}

}  // namespace
}  // namespace q3::test
