// Byte-identical output whatever the thread count: every benchmark option set
// (bench/option-sets.json) runs the real q3map2 on real oacmp maps with -threads 1, -threads 2 and
// -threads 2 again, and every file the runs leave in maps/ (the BSP, lightmap or JSON outputs)
// must match byte for byte.
#include "option_sets.h"
#include "output_snapshot.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;
using q3::test::FolderSnapshot;
using q3::test::OptionSet;

// The cheapest oacmp maps (about 1.3, 2.6 and 2.6 s of CPU for -light -fast); a sanitizer build
// (which samples the per-map tests) checks the first only.
const std::vector<std::string> kMaps = {"oacmpdm5", "oacmpctf2", "oacmpdm1"};
const std::vector<int> kThreadCounts = {1, 2, 2};

struct DeterminismCase {
    std::string map;
    OptionSet set;
    std::vector<OptionSet> allSets;  // to find the set that runs first
};

std::vector<std::string> casesMaps() {
    if (q3::test::realBspsAreSampled()) return {kMaps.front()};
    return kMaps;
}

// The sets checked in this build: all of them, less those marked "sampledBuilds": "skip" where the
// real maps are sampled (their code paths are covered there by a cheaper or wider set).
std::vector<OptionSet> checkedSets(const std::vector<OptionSet>& sets) {
    std::vector<OptionSet> checked;
    for (const OptionSet& set : sets)
        if (!(set.skipWhenSampled && q3::test::realBspsAreSampled())) checked.push_back(set);
    return checked;
}

std::vector<DeterminismCase> determinismCases() {
    std::vector<OptionSet> sets;
    try {
        sets = q3::test::readOptionSets(q3::test::optionSetsFile());
    } catch (const std::exception&) {
        return {};  // DeterminismSetup.OptionSetsAreReadable reports it
    }
    std::vector<DeterminismCase> cases;
    for (const std::string& map : casesMaps())
        for (const OptionSet& set : checkedSets(sets)) cases.push_back({map, set, sets});
    return cases;
}

std::string quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Runs one option set on `bsp`; fails the test (fatal in the caller) on a non-zero exit.
void runSet(const OptionSet& set, int threads, const fs::path& bsp) {
    std::string line = quote(q3::test::q3map2Exe().string()) + " -threads " + std::to_string(threads) +
                       " -fs_basepath " + quote(q3::test::openArenaBase().string()) + " -fs_game baseoa";
    for (const std::string& arg : set.args) line += " " + quote(arg);
    line += " " + quote(bsp.string());
    std::string output;
    const int rc = q3::test::runCommand(line, &output);
    if (output.size() > 3000) output = "..." + output.substr(output.size() - 3000);
    ASSERT_EQ(rc, 0) << line << "\n" << output;
}

// Copies the shipped BSP (and its .map source, whose lights the light stage reads) into
// <dir>/baseoa/maps/; returns the BSP's path there.
fs::path stageMap(const std::string& map, const fs::path& dir) {
    const fs::path maps = dir / "baseoa" / "maps";
    fs::create_directories(maps);
    const fs::path bsp = maps / (map + ".bsp");
    fs::copy_file(q3::test::realBsp(map), bsp);
    for (const fs::path& source : q3::test::oacmpMapSources())
        if (source.stem() == map) fs::copy_file(source, maps / source.filename());
    return bsp;
}

class Determinism : public ::testing::TestWithParam<DeterminismCase> {};

TEST_P(Determinism, SameBytesWithOneTwoAndTwoAgainThreads) {
    const DeterminismCase& c = GetParam();
    const fs::path root = q3::test::tempDir();
    const OptionSet* first = nullptr;
    for (const OptionSet& s : c.allSets)
        if (s.name == c.set.after) first = &s;
    ASSERT_TRUE(c.set.after.empty() || first) << c.set.name << " runs after unknown set " << c.set.after;

    std::vector<FolderSnapshot> outputs;
    FolderSnapshot input;
    for (size_t run = 0; run < kThreadCounts.size(); ++run) {
        const fs::path dir = root / ("run" + std::to_string(run));
        const fs::path bsp = stageMap(c.map, dir);
        if (run == 0) input = q3::test::snapshotFolder(bsp.parent_path());
        if (first) {
            ASSERT_NO_FATAL_FAILURE(runSet(*first, kThreadCounts[run], bsp));
        }
        ASSERT_NO_FATAL_FAILURE(runSet(c.set, kThreadCounts[run], bsp));
        outputs.push_back(q3::test::snapshotFolder(bsp.parent_path()));
        fs::remove_all(dir);
    }
    // The set must have written something, or identical outputs prove nothing.
    EXPECT_FALSE(q3::test::describeDifferences(input, outputs[0]).empty()) << c.set.name << " wrote nothing";
    size_t bytes = 0;
    for (const auto& [name, data] : outputs[0]) bytes += data.size();
    std::printf("%s %s: %zu files, %zu bytes compared\n", c.map.c_str(), c.set.name.c_str(), outputs[0].size(),
                bytes);
    for (size_t run = 1; run < outputs.size(); ++run) {
        EXPECT_EQ(q3::test::describeDifferences(outputs[run - 1], outputs[run]), "")
            << c.map << " " << c.set.name << ": -threads " << kThreadCounts[run - 1] << " and -threads "
            << kThreadCounts[run] << " (run " << run + 1 << ") differ";
    }
}

INSTANTIATE_TEST_SUITE_P(OptionSets, Determinism, ::testing::ValuesIn(determinismCases()),
                         [](const ::testing::TestParamInfo<DeterminismCase>& info) {
                             std::string name = info.param.map + "_" + info.param.set.name;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

// The shared file parses and every map and set is registered, so an unreadable file or a missing
// data cache fails instead of silently running no determinism test.
TEST(DeterminismSetup, OptionSetsAreReadableAndEveryCaseIsRegistered) {
    const std::vector<OptionSet> sets = q3::test::readOptionSets(q3::test::optionSetsFile());
    EXPECT_GE(sets.size(), 6u);
    for (const std::string& map : casesMaps()) EXPECT_TRUE(fs::exists(q3::test::realBsp(map)));
    const std::vector<OptionSet> checked = checkedSets(sets);
    EXPECT_EQ(determinismCases().size(), casesMaps().size() * checked.size());
    const auto has = [](const OptionSet& s, const char* option) {
        return std::find(s.args.begin(), s.args.end(), option) != s.args.end();
    };
    bool hasLightSh = false, hasJson = false, hasRelease = false;
    for (const OptionSet& s : checked) {
        hasLightSh = hasLightSh || has(s, "-sh");
        hasJson = hasJson || (!s.args.empty() && s.args.front() == "-json");
        // The release options together (radiosity, dirt, deluxe maps) in every build.
        hasRelease = hasRelease || (has(s, "-bounce") && has(s, "-dirty") && has(s, "-deluxe"));
    }
    EXPECT_TRUE(hasLightSh);
    EXPECT_TRUE(hasJson);
    EXPECT_TRUE(hasRelease);
}

TEST(DeterminismSetup, BadOptionSetFilesAreRejected) {
    const fs::path dir = q3::test::tempDir();
    const auto write = [&](const std::string& text) {
        const fs::path file = dir / "sets.json";
        FILE* f = std::fopen(file.c_str(), "wb");
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
        return file;
    };
    EXPECT_THROW(q3::test::readOptionSets(dir / "absent.json"), std::runtime_error);
    EXPECT_THROW(q3::test::readOptionSets(write("{\"sets\": [1, 2]}")), std::runtime_error);
    EXPECT_THROW(q3::test::readOptionSets(write("{\"sets\": {\"a\": {\"args\": []}}}")), std::runtime_error);
    EXPECT_THROW(q3::test::readOptionSets(write("{\"sets\": {\"a\": {\"args\": [\"-x\"], \"after\": \"b\"}}}")),
                 std::runtime_error);
    EXPECT_THROW(q3::test::readOptionSets(write("{\"sets\": {\"a\": {\"args\": [\"-x\"], \"sampledBuilds\": \"run\"}}}")),
                 std::runtime_error);
    EXPECT_THROW(q3::test::readOptionSets(write("{\"sets\": {\"a\": {\"args\": [\"-x\"], \"sampledBuilds\": true}}}")),
                 std::runtime_error);
    const auto skipped = q3::test::readOptionSets(
        write("{\"sets\": {\"a\": {\"args\": [\"-x\"], \"sampledBuilds\": \"skip\"}, \"b\": {\"args\": [\"-y\"]}}}"));
    ASSERT_EQ(skipped.size(), 2u);
    EXPECT_TRUE(skipped[0].skipWhenSampled);
    EXPECT_FALSE(skipped[1].skipWhenSampled);
    const auto sets = q3::test::readOptionSets(
        write("{\"sets\": {\"u\": {\"args\": [\"-json\", \"-unpack\"]}, \"p\": {\"args\": [\"-json\"], \"after\": \"u\"}}}"));
    ASSERT_EQ(sets.size(), 2u);
    EXPECT_EQ(sets[1].after, "u");
    EXPECT_EQ(sets[0].args[1], "-unpack");
}

// The comparison itself catches a single changed byte and names the lump it lies in.
TEST(DeterminismSetup, DifferencesAreFoundAndLocated) {
    std::vector<uint8_t> bsp(8 + 8 * 18 + 64, 0);
    std::memcpy(bsp.data(), "IBSP", 4);
    bsp[4] = 46;
    const int32_t offset = 8 + 8 * 17, length = 64;
    std::memcpy(bsp.data() + 8 + 8 * 14, &offset, 4);  // lump 14 (lightmaps) covers the payload
    std::memcpy(bsp.data() + 12 + 8 * 14, &length, 4);
    FolderSnapshot a{{"maps/x.bsp", bsp}, {"maps/x/a.json", {1, 2, 3}}};
    FolderSnapshot b = a;
    EXPECT_EQ(q3::test::describeDifferences(a, b), "");
    b["maps/x.bsp"][offset + 10] ^= 1;
    const std::string report = q3::test::describeDifferences(a, b);
    EXPECT_NE(report.find("maps/x.bsp"), std::string::npos) << report;
    EXPECT_NE(report.find("lump 14"), std::string::npos) << report;
    EXPECT_NE(report.find(std::to_string(offset + 10)), std::string::npos) << report;
    b = a;
    b.erase("maps/x/a.json");
    EXPECT_NE(q3::test::describeDifferences(a, b).find("missing"), std::string::npos);
    b = a;
    b["maps/x/extra.png"] = {0};
    EXPECT_NE(q3::test::describeDifferences(a, b).find("only in the second run"), std::string::npos);
}

}  // namespace
