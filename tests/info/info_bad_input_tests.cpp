// Malformed inputs: each must end q3map2 -info with exactly one "ERROR: ..." line on stderr that
// names the file, a non-zero exit code that is not a signal, and the input left byte-for-byte
// as it was.
#include "info_test_files.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

namespace q3::test {
namespace {

namespace fs = std::filesystem;

struct BadCase {
    std::string name;
    std::function<Bytes(const Bytes&)> make;  // from a valid v46 file
};

Bytes baseMap() {
    // A small map with every record kind the mutations below need.
    fs::path best;
    for (const auto& p : allRealBsps()) {
        Bytes b = readBytes(p);
        bool ok = true;
        for (int lump : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 16}) ok = ok && lumpEntry(b, lump).length > 0;
        if (ok && (best.empty() || fs::file_size(p) < fs::file_size(best))) best = p;
    }
    EXPECT_FALSE(best.empty());
    return readBytes(best);
}

size_t recordAt(const Bytes& file, int lump, size_t index, size_t recordSize) {
    return static_cast<size_t>(lumpEntry(file, lump).offset) + index * recordSize;
}

// Mutates one int32 field of record 0 of a lump.
BadCase field(std::string name, int lump, size_t recordSize, size_t fieldOffset,
              std::function<int32_t(const Bytes&)> value) {
    return {std::move(name), [=](const Bytes& f) {
                Bytes b = f;
                put32(b, recordAt(b, lump, 0, recordSize) + fieldOffset, value(b));
                return b;
            }};
}

BadCase floatField(std::string name, int lump, size_t recordSize, size_t fieldOffset, float value) {
    return {std::move(name), [=](const Bytes& f) {
                Bytes b = f;
                putFloat(b, recordAt(b, lump, 0, recordSize) + fieldOffset, value);
                return b;
            }};
}

BadCase entry(std::string name, int lump, std::function<LumpEntry(const Bytes&, LumpEntry)> change) {
    return {std::move(name), [=](const Bytes& f) {
                Bytes b = f;
                setLumpEntry(b, lump, change(b, lumpEntry(b, lump)));
                return b;
            }};
}

int32_t count(const Bytes& b, int lump, int32_t recordSize) { return lumpEntry(b, lump).length / recordSize; }

std::vector<BadCase> badCases() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<BadCase> c;
    c.push_back({"empty", [](const Bytes&) { return Bytes{}; }});
    c.push_back({"three_bytes", [](const Bytes& f) { return Bytes(f.begin(), f.begin() + 3); }});
    c.push_back({"truncated_header", [](const Bytes& f) { return Bytes(f.begin(), f.begin() + 100); }});
    c.push_back({"truncated_lumps", [](const Bytes& f) { return Bytes(f.begin(), f.begin() + f.size() / 2); }});
    c.push_back({"wrong_ident", [](const Bytes& f) {
                     Bytes b = f;
                     std::memcpy(b.data(), "XBSP", 4);
                     return b;
                 }});
    c.push_back({"rbsp_ident", [](const Bytes& f) {
                     Bytes b = f;
                     std::memcpy(b.data(), "RBSP", 4);
                     return b;
                 }});
    c.push_back({"version_45", [](const Bytes& f) {
                     Bytes b = f;
                     put32(b, 4, 45);
                     return b;
                 }});
    c.push_back({"version_99", [](const Bytes& f) {
                     Bytes b = f;
                     put32(b, 4, 99);
                     return b;
                 }});
    c.push_back(entry("planes_offset_past_end", 2, [](const Bytes& b, LumpEntry e) {
        return LumpEntry{static_cast<int32_t>(b.size()) + 64, e.length};
    }));
    c.push_back(entry("shaders_length_past_end", 1, [](const Bytes& b, LumpEntry e) {
        return LumpEntry{e.offset, static_cast<int32_t>(b.size()) * 72};
    }));
    c.push_back(entry("negative_offset", 10, [](const Bytes&, LumpEntry e) { return LumpEntry{-44, e.length}; }));
    c.push_back(entry("negative_length", 11, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, -4}; }));
    c.push_back(entry("planes_not_multiple", 2, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, e.length - 4}; }));
    c.push_back(entry("shaders_not_multiple", 1, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, e.length - 8}; }));
    c.push_back(entry("drawverts_not_multiple", 10, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, e.length - 4}; }));
    c.push_back(entry("surfaces_not_multiple", 13, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, e.length - 4}; }));
    c.push_back(entry("nodes_not_multiple", 3, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, e.length - 4}; }));
    c.push_back(entry("lightgrid_not_multiple", 15, [](const Bytes&, LumpEntry e) { return LumpEntry{e.offset, e.length - 4}; }));
    c.push_back(field("surface_shader_out_of_range", 13, 104, 0, [](const Bytes& b) { return count(b, 1, 72) + 5; }));
    c.push_back(field("surface_verts_out_of_range", 13, 104, 12, [](const Bytes& b) { return count(b, 10, 44); }));
    c.push_back(field("surface_negative_first_index", 13, 104, 20, [](const Bytes&) { return -7; }));
    c.push_back(field("node_plane_out_of_range", 3, 36, 0, [](const Bytes& b) { return count(b, 2, 16) + 1; }));
    c.push_back(field("node_child_leaf_out_of_range", 3, 36, 4, [](const Bytes& b) { return -(count(b, 4, 48) + 10); }));
    c.push_back(field("leaf_surfaces_out_of_range", 4, 48, 32, [](const Bytes& b) { return count(b, 5, 4) + 1; }));
    c.push_back(field("leafsurface_index_out_of_range", 5, 4, 0, [](const Bytes& b) { return count(b, 13, 104) + 3; }));
    c.push_back(field("leafbrush_index_out_of_range", 6, 4, 0, [](const Bytes& b) { return count(b, 8, 12) + 3; }));
    c.push_back(field("brush_sides_out_of_range", 8, 12, 0, [](const Bytes& b) { return count(b, 9, 8); }));
    c.push_back(field("brushside_plane_out_of_range", 9, 8, 0, [](const Bytes& b) { return count(b, 2, 16) + 100; }));
    c.push_back(field("model_surfaces_out_of_range", 7, 40, 24, [](const Bytes& b) { return count(b, 13, 104) + 1; }));
    c.push_back(field("index_past_surface_verts", 11, 4, 0, [](const Bytes&) { return 1 << 28; }));
    c.push_back(floatField("nan_plane", 2, 16, 0, nan));
    c.push_back(floatField("infinite_plane_dist", 2, 16, 12, inf));
    c.push_back(floatField("nan_drawvert", 10, 44, 4, nan));
    c.push_back(floatField("nan_model_bounds", 7, 40, 0, nan));
    c.push_back({"visibility_header_too_big", [](const Bytes& f) {
                     Bytes b = f;
                     put32(b, recordAt(b, 16, 0, 1), 1 << 20);
                     return b;
                 }});
    c.push_back({"entities_unbalanced", [](const Bytes& f) {
                     Bytes b = f;
                     size_t at = static_cast<size_t>(lumpEntry(b, 0).offset);
                     b[at] = '}';  // the first '{' becomes a stray '}'
                     return b;
                 }});
    c.push_back({"bspx_entry_past_end", [](const Bytes& f) {
                     Bytes b = withBspxLump(f, "LIGHTGRID_SH", Bytes(40, 0));
                     size_t directory = endOfLumps(f);
                     put32(b, directory + 8 + 28, static_cast<int32_t>(b.size()));  // length past the end
                     return b;
                 }});
    c.push_back({"bspx_count_too_large", [](const Bytes& f) {
                     Bytes b = withBspxLump(f, "RGBLIGHTING", Bytes(16, 1));
                     put32(b, endOfLumps(f) + 4, 1000000);
                     return b;
                 }});
    c.push_back({"bspx_name_not_terminated", [](const Bytes& f) {
                     Bytes b = withBspxLump(f, "LIGHTGRID_SH", Bytes(8, 0));
                     std::memset(b.data() + endOfLumps(f) + 8, 'A', 24);
                     return b;
                 }});
    const float mins[3] = {0, 0, 0}, size[3] = {64, 64, 128};
    const int32_t bounds[3] = {2, 2, 2};
    c.push_back({"sh_lump_short", [=](const Bytes& f) {
                     Bytes sh = shGridLump(mins, size, bounds, std::vector<std::array<float, 3>>(8));
                     sh.resize(sh.size() - 108);
                     return withShLump(f, sh);
                 }});
    c.push_back({"sh_lump_count_mismatch", [=](const Bytes& f) {
                     Bytes sh = shGridLump(mins, size, bounds, std::vector<std::array<float, 3>>(8));
                     put32(sh, 36, 7);
                     return withShLump(f, sh);
                 }});
    c.push_back({"sh_lump_zero_cell", [=](const Bytes& f) {
                     const float zero[3] = {64, 0, 128};
                     return withShLump(f, shGridLump(mins, zero, bounds, std::vector<std::array<float, 3>>(8)));
                 }});
    c.push_back({"sh_lump_nan_coefficient", [=](const Bytes& f) {
                     std::vector<std::array<float, 3>> points(8);
                     points[5] = {1, nan, 1};
                     return withShLump(f, shGridLump(mins, size, bounds, points));
                 }});
    c.push_back({"sh_lump_header_only_part", [=](const Bytes& f) { return withShLump(f, Bytes(20, 0)); }});
    c.push_back({"sh_bspx_bad", [=](const Bytes& f) {
                     Bytes sh = shGridLump(mins, size, bounds, std::vector<std::array<float, 3>>(8));
                     put32(sh, 24, -2);
                     return withBspxLump(f, "LIGHTGRID_SH", sh);
                 }});
    return c;
}

void expectOneErrorLine(const RunResult& run, const std::string& fileName) {
    EXPECT_NE(run.exitCode, 0);
    EXPECT_LT(run.exitCode, 128) << "killed by a signal";
    EXPECT_GT(run.exitCode, 0);
    ASSERT_FALSE(run.err.empty());
    EXPECT_EQ(run.err.rfind("ERROR: ", 0), 0u) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "more than one line: " << run.err;
    EXPECT_NE(run.err.find(fileName), std::string::npos) << run.err;
}

TEST(InfoBadInput, EveryMalformedFileGivesOneErrorLine) {
    const Bytes base = baseMap();
    ASSERT_FALSE(base.empty());
    const fs::path dir = tempDir();
    std::vector<BadCase> cases = badCases();
    ASSERT_GE(cases.size(), 25u);
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path file = dir / (c.name + ".bsp");
        const Bytes bytes = c.make(base);
        writeBytes(file, bytes);
        RunResult run = runQ3map2({"-info", file.string()}, dir);
        expectOneErrorLine(run, file.string());
        EXPECT_EQ(run.exitCode, 1);
        EXPECT_EQ(readBytes(file), bytes) << "input modified";
        // Nothing but the input (and the captured streams) may appear in the folder.
        for (const auto& entry : fs::directory_iterator(dir))
            EXPECT_TRUE(entry.path() == dir / "run" || entry.path().extension() == ".bsp") << entry.path();
    }
}

TEST(InfoBadInput, DirectoryAndMissingFile) {
    const fs::path dir = tempDir();
    fs::create_directories(dir / "folder.bsp");
    RunResult run = runQ3map2({"-info", (dir / "folder.bsp").string()}, dir);
    expectOneErrorLine(run, (dir / "folder.bsp").string());
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_TRUE(fs::is_directory(dir / "folder.bsp"));

    run = runQ3map2({"-info", (dir / "missing.bsp").string()}, dir);
    expectOneErrorLine(run, (dir / "missing.bsp").string());
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_FALSE(fs::exists(dir / "missing.bsp"));
}

TEST(InfoBadInput, ForceDoesNotHideStructuralDamage) {
    const Bytes base = baseMap();
    const fs::path dir = tempDir();
    Bytes b = base;
    setLumpEntry(b, 2, {lumpEntry(b, 2).offset, lumpEntry(b, 2).length - 4});
    writeBytes(dir / "planes.bsp", b);
    RunResult run = runQ3map2({"-force", "-info", (dir / "planes.bsp").string()}, dir);
    expectOneErrorLine(run, (dir / "planes.bsp").string());
}

}  // namespace
}  // namespace q3::test
