// -info on the real OpenArena maps: every printed count and size is checked against the lump
// directory read by the test itself, and the legacy grid count against the engine's formula.
#include "info_test_files.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <sstream>

namespace q3::test {
namespace {

struct Printed {
    long long count = -1, bytes = -1;
};

std::map<std::string, Printed> parseLumpLines(const std::string& out) {
    std::map<std::string, Printed> lines;
    static const std::regex row(R"(^\s*(\d+) (\w+)\s+(\d+)( \*)?$)");
    static const std::regex vis(R"(^\s+visibility\s+(\d+)$)");
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_match(line, m, row)) lines[m[2]] = {std::stoll(m[1]), std::stoll(m[3])};
        else if (std::regex_match(line, m, vis)) lines["visibility"] = {-1, std::stoll(m[1])};
    }
    return lines;
}

// Top-level '{' outside quoted strings: one per entity.
long long countEntities(const Bytes& text) {
    long long n = 0;
    bool quoted = false;
    int depth = 0;
    for (uint8_t c : text) {
        if (c == '"') quoted = !quoted;
        else if (!quoted && c == '{' && depth++ == 0) ++n;
        else if (!quoted && c == '}') --depth;
    }
    return n;
}

long long expectedGridPoints(const Bytes& file) {
    Bytes models = lumpData(file, 7);
    if (models.size() < 40) return 0;
    float size[3] = {64, 64, 128};
    Bytes ents = lumpData(file, 0);
    std::string text(ents.begin(), ents.end());
    std::smatch m;
    // The worldspawn is the first entity; its "gridsize" key, if any, comes before the first '}'.
    std::string world = text.substr(0, text.find('}'));
    if (std::regex_search(world, m, std::regex(R"re("gridsize"\s+"([^"]*)")re", std::regex::icase))) {
        std::istringstream in(m[1].str());
        for (float& s : size) in >> s;
    }
    long long points = 1;
    for (int i = 0; i < 3; ++i) {
        float mins = getFloat(models, static_cast<size_t>(i) * 4), maxs = getFloat(models, 12 + static_cast<size_t>(i) * 4);
        float origin = size[i] * std::ceil(mins / size[i]);
        float top = size[i] * std::floor(maxs / size[i]);
        points *= static_cast<int>((top - origin) / size[i] + 1);
    }
    return points;
}

TEST(InfoRealData, CountsMatchTheLumpDirectory) {
    const std::vector<std::filesystem::path> maps = allRealBsps();
    ASSERT_GE(maps.size(), 100u);
    const std::filesystem::path scratch = tempDir();
    struct Record {
        const char* name;
        int lump;
        long long size;
    };
    const Record records[] = {{"models", 7, 40},       {"shaders", 1, 72},      {"brushes", 8, 12},
                              {"brushsides", 9, 8},    {"fogs", 12, 72},        {"planes", 2, 16},
                              {"nodes", 3, 36},        {"leafs", 4, 48},        {"leafsurfaces", 5, 4},
                              {"leafbrushes", 6, 4},   {"drawsurfaces", 13, 104}, {"drawverts", 10, 44},
                              {"drawindexes", 11, 4},  {"lightgrid", 15, 8},    {"lightmaps", 14, 128 * 128 * 3}};
    int gridMatches = 0;
    for (const auto& path : maps) {
        SCOPED_TRACE(path.string());
        const Bytes file = readBytes(path);
        RunResult run = runQ3map2({"-info", path.string()}, scratch);
        ASSERT_EQ(run.exitCode, 0) << run.err;
        EXPECT_EQ(run.err, "");
        std::map<std::string, Printed> lines = parseLumpLines(run.out);
        for (const Record& r : records) {
            long long length = lumpEntry(file, r.lump).length;
            ASSERT_TRUE(lines.count(r.name)) << r.name;
            EXPECT_EQ(lines[r.name].bytes, r.lump == 14 ? length : length / r.size * r.size) << r.name;
            EXPECT_EQ(lines[r.name].count, length / r.size) << r.name;
        }
        EXPECT_EQ(lines["entdata"].bytes, lumpEntry(file, 0).length);
        EXPECT_EQ(lines["entdata"].count, countEntities(lumpData(file, 0)));
        EXPECT_EQ(lines["visibility"].bytes, lumpEntry(file, 16).length);
        EXPECT_NE(run.out.find("Header: IBSP version " + std::to_string(get32(file, 4))), std::string::npos);
        std::string nameLine = path.string();
        nameLine.insert(nameLine.begin(), '\n');
        nameLine.push_back('\n');
        EXPECT_NE(run.out.find(nameLine), std::string::npos);
        EXPECT_NE(run.out.find("File size: " + std::to_string(file.size()) + " bytes"), std::string::npos);

        long long stored = lumpEntry(file, 15).length / 8;
        long long expected = expectedGridPoints(file);
        std::string gridLine = "Legacy grid: " + std::to_string(stored) + " points stored, engine expects " +
                               std::to_string(expected);
        EXPECT_NE(run.out.find(gridLine), std::string::npos) << run.out;
        gridMatches += stored == expected;
        EXPECT_EQ(run.out.find("count mismatch") == std::string::npos, stored == expected || stored == 0);
    }
    // The shipped maps were lit by q3map2, whose grid always has the engine's size.
    EXPECT_GE(gridMatches, static_cast<int>(maps.size()) * 9 / 10);
}

// The smallest real map, as the base of the synthetic SH files.
Bytes smallestRealMap() {
    std::filesystem::path best;
    for (const auto& p : allRealBsps())
        if (best.empty() || std::filesystem::file_size(p) < std::filesystem::file_size(best)) best = p;
    return readBytes(best);
}

std::string g(double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
}

TEST(InfoShGrid, StatisticsOfLump18AndOfTheBspxLump) {
    const Bytes base = smallestRealMap();
    const float mins[3] = {-64, -32, 0}, size[3] = {32, 32, 64};
    const int32_t bounds[3] = {2, 2, 3};
    std::vector<std::array<float, 3>> coeff0(12);
    double sum = 0;
    for (size_t i = 0; i < coeff0.size(); ++i) {
        float v = (i % 4 == 1) ? 0.0f : 0.25f * static_cast<float>(i);  // points 0, 1, 5, 9 are all zero
        coeff0[i] = {v, v * 0.5f, v * 2.0f};
        sum += v * 3.5;
    }
    const Bytes sh = shGridLump(mins, size, bounds, coeff0);
    const std::filesystem::path dir = tempDir();

    const Bytes v47 = withShLump(base, sh);
    writeBytes(dir / "sh47.bsp", v47);
    const Bytes bspx = withBspxLump(base, "LIGHTGRID_SH", sh);
    writeBytes(dir / "shbspx.bsp", bspx);

    for (const char* name : {"sh47.bsp", "shbspx.bsp"}) {
        SCOPED_TRACE(name);
        RunResult run = runQ3map2({"-info", (dir / name).string()}, dir);
        ASSERT_EQ(run.exitCode, 0) << run.err;
        EXPECT_NE(run.out.find("  bounds       2 x 2 x 3\n"), std::string::npos) << run.out;
        EXPECT_NE(run.out.find("  cell size    32 32 64\n"), std::string::npos);
        EXPECT_NE(run.out.find("  mins         -64 -32 0\n"), std::string::npos);
        EXPECT_NE(run.out.find("  points       12\n"), std::string::npos);
        EXPECT_NE(run.out.find("  bytes        " + std::to_string(sh.size()) + "\n"), std::string::npos);
        std::string stats = "  coefficient 0 min 0 max " + g(0.25 * 11 * 2) + " mean " + g(sum / 36.0) + "\n";
        EXPECT_NE(run.out.find(stats), std::string::npos) << stats << run.out;
        EXPECT_NE(run.out.find("  all-zero points 4\n"), std::string::npos);
    }
    RunResult v47run = runQ3map2({"-info", (dir / "sh47.bsp").string()}, dir);
    EXPECT_NE(v47run.out.find("Header: IBSP version 47, 19 lump entries"), std::string::npos);
    EXPECT_NE(v47run.out.find("SH grid (lump 18):"), std::string::npos);
    RunResult bspxRun = runQ3map2({"-info", (dir / "shbspx.bsp").string()}, dir);
    EXPECT_NE(bspxRun.out.find("BSPX lumps: 1\n  LIGHTGRID_SH"), std::string::npos) << bspxRun.out;
    EXPECT_NE(bspxRun.out.find("SH grid (BSPX LIGHTGRID_SH):"), std::string::npos);
}

// q3map_foliage surfaces (MST_FOLIAGE) are read and counted beside the other surface types.
TEST(InfoSurfaces, FoliageSurfacesAreCounted) {
    const std::filesystem::path dir = tempDir();
    const std::filesystem::path golden = std::filesystem::path(Q3MAP_SOURCE_DIR) / "bsp-samples/golden/foliage.bsp";
    std::filesystem::copy_file(golden, dir / "foliage.bsp");
    RunResult run = runQ3map2({"-info", (dir / "foliage.bsp").string()}, dir);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("        2   foliage surfaces\n"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("        1   patch surfaces\n"), std::string::npos) << run.out;
}

TEST(InfoCommandLine, MapPathWithoutExtensionOrAsMap) {
    const std::filesystem::path dir = tempDir();
    writeBytes(dir / "small.bsp", smallestRealMap());
    for (const std::string& arg : std::vector<std::string>{(dir / "small").string(), (dir / "small.map").string()}) {
        RunResult run = runQ3map2({"-info", arg}, dir);
        EXPECT_EQ(run.exitCode, 0) << run.err;
        EXPECT_NE(run.out.find((dir / "small.bsp").string()), std::string::npos);
    }
}

TEST(InfoCommandLine, CommonOptionsBeforeTheStage) {
    const std::filesystem::path dir = tempDir();
    writeBytes(dir / "small.bsp", smallestRealMap());
    RunResult run = runQ3map2({"-v", "-threads", "1", "-force", "-info", (dir / "small.bsp").string()}, dir);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_NE(run.out.find("Abstracted BSP file components"), std::string::npos);
}

TEST(InfoCommandLine, UsageErrorsExitWithTwo) {
    const std::filesystem::path dir = tempDir();
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{}, "no stage given: expected a stage switch such as -light or -info before the map file (see q3map2 -help)"},
        {{"-info"}, "-info needs a map file as its last argument (-info [options] <filename.bsp>)"},
        {{"-info", "-fast", "m.bsp"}, "unknown option '-fast' (see q3map2 -help info)"},
        {{"-info", "-v", "m.bsp"}, "common option -v must come before the stage switch -info"},
        {{"-bsp", "-custinfoparms", "m.map"}, "-custinfoparms is a q3map2 option this build does not implement yet"},
        {{"-threads", "x", "-info", "m.bsp"}, "-threads: 'x' is not an integer (-threads <N>)"},
    };
    for (const Case& c : cases) {
        RunResult run = runQ3map2(c.args, dir);
        EXPECT_EQ(run.exitCode, 2);
        EXPECT_EQ(run.err, "ERROR: " + c.message + "\n");
        EXPECT_EQ(run.out, "");
    }
    RunResult help = runQ3map2({"-help", "light"}, dir);
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.out.find("  -gridscalesh <F>"), std::string::npos);
    EXPECT_EQ(help.err, "");
}

}  // namespace
}  // namespace q3::test
