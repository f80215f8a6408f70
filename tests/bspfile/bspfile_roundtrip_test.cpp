// Header layouts, lump 18 and the BSPX trailer survive a write/read round trip byte for byte.
#include "synthetic_bsp.h"

#include "file_io.h"
#include "sh_grid_lump.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace q3::bsp::test {
namespace {

std::vector<std::vector<uint8_t>> allLumps(const Bsp& bsp) {
    std::vector<std::vector<uint8_t>> out;
    for (int i = 0; i < kMaxLumps; ++i) out.push_back(lumpBytes(bsp, i));
    return out;
}

void expectSameLumps(const Bsp& a, const Bsp& b) {
    for (int i = 0; i < kMaxLumps; ++i) EXPECT_EQ(lumpBytes(a, i), lumpBytes(b, i)) << "lump " << lumpName(i);
    ASSERT_EQ(a.bspx.size(), b.bspx.size());
    for (size_t i = 0; i < a.bspx.size(); ++i) {
        EXPECT_EQ(a.bspx[i].name, b.bspx[i].name);
        EXPECT_EQ(a.bspx[i].data, b.bspx[i].data);
    }
}

// Checks the file image against the raw header: header size, alignment, empty entries, payloads.
void expectImageMatches(const std::vector<uint8_t>& image, const Bsp& bsp) {
    const std::vector<RawEntry> entries = rawEntries(image, bsp.headerLumps);
    int32_t version;
    std::memcpy(&version, image.data() + 4, 4);
    EXPECT_EQ(version, bsp.version);
    EXPECT_EQ(std::memcmp(image.data(), "IBSP", 4), 0);
    for (int i = 0; i < bsp.headerLumps; ++i) {
        const RawEntry& e = entries[static_cast<size_t>(i)];
        if (e.length == 0) {
            EXPECT_EQ(e.offset, 0) << "empty lump " << lumpName(i) << " must have offset 0";
        } else {
            EXPECT_EQ(e.offset % 4, 0) << lumpName(i);
            EXPECT_GE(static_cast<size_t>(e.offset), 8 + 8 * static_cast<size_t>(bsp.headerLumps)) << lumpName(i);
        }
        EXPECT_EQ(rawLump(image, e), lumpBytes(bsp, i)) << lumpName(i);
    }
}

Bsp roundTrip(const Bsp& bsp, std::vector<uint8_t>* imageOut = nullptr) {
    const std::vector<uint8_t> image = serializeBsp(bsp);
    expectImageMatches(image, bsp);
    Bsp back = parseBsp(image, "roundtrip.bsp");
    EXPECT_EQ(back.version, bsp.version);
    EXPECT_EQ(back.headerLumps, bsp.headerLumps);
    expectSameLumps(bsp, back);
    EXPECT_EQ(serializeBsp(back), image) << "second write differs";
    if (imageOut) *imageOut = image;
    return back;
}

TEST(BspRoundTrip, Version46With17Entries) {
    Bsp bsp = makeSyntheticBsp();
    std::vector<uint8_t> image;
    roundTrip(bsp, &image);
    EXPECT_EQ(rawEntries(image, 17)[LUMP_ENTITIES].offset, 144);
}

TEST(BspRoundTrip, Version46With18EntriesAndEmptyLump17) {
    Bsp bsp = makeSyntheticBsp();
    bsp.headerLumps = 18;
    std::vector<uint8_t> image;
    roundTrip(bsp, &image);
    EXPECT_EQ(rawEntries(image, 18)[LUMP_ENTITIES].offset, 152);
    EXPECT_EQ(rawEntries(image, 18)[LUMP_ADVERTISEMENTS].length, 0);
}

TEST(BspRoundTrip, Version47With18EntriesKeepsAdvertisements) {
    Bsp bsp = makeSyntheticBsp();
    bsp.version = kVersionQL;
    bsp.headerLumps = 18;
    Advertisement ad{};
    ad.cellId = 7;
    ad.normal[0] = 1.0f;
    std::strncpy(ad.model, "models/ads/board.md3", sizeof ad.model - 1);
    bsp.lump17.resize(sizeof ad);
    std::memcpy(bsp.lump17.data(), &ad, sizeof ad);
    Bsp back = roundTrip(bsp);
    EXPECT_TRUE(back.shGrid.empty());
}

TEST(BspRoundTrip, Version47With19EntriesCarriesShGrid) {
    Bsp bsp = makeSyntheticBsp();
    attachShGrid(bsp, makeShGridLump(3, 2, 2));
    EXPECT_EQ(bsp.version, kVersionQL);
    EXPECT_EQ(bsp.headerLumps, 19);
    std::vector<uint8_t> image;
    Bsp back = roundTrip(bsp, &image);
    const std::vector<RawEntry> entries = rawEntries(image, 19);
    EXPECT_EQ(entries[LUMP_ENTITIES].offset, 160);
    EXPECT_EQ(entries[LUMP_ADVERTISEMENTS].offset, 0);
    EXPECT_EQ(entries[LUMP_ADVERTISEMENTS].length, 0);
    EXPECT_EQ(entries[LUMP_LIGHTGRID_SH].length, static_cast<int32_t>(40 + 108 * 12));
    EXPECT_EQ(back.shGrid, makeShGridLump(3, 2, 2));
    EXPECT_EQ(sh::checkGridLump(back.shGrid.data(), back.shGrid.size()), "");

    detachShGrid(back);
    EXPECT_EQ(back.shGrid.capacity(), 0u) << "the dropped grid's memory is released, not kept reserved";
    EXPECT_EQ(back.version, kVersionQ3);
    EXPECT_EQ(back.headerLumps, 17);
    roundTrip(back);
}

TEST(BspRoundTrip, Version47With19EntriesAllExtrasEmpty) {
    Bsp bsp = makeSyntheticBsp();
    bsp.version = kVersionQL;
    bsp.headerLumps = 19;
    Bsp back = roundTrip(bsp);
    EXPECT_TRUE(back.shGrid.empty());
}

TEST(BspRoundTrip, Version47With17EntriesLikeEnemyTerritory) {
    Bsp bsp = makeSyntheticBsp();
    bsp.version = kVersionQL;
    bsp.headerLumps = 17;
    std::vector<uint8_t> image;
    roundTrip(bsp, &image);
    EXPECT_EQ(rawEntries(image, 17)[LUMP_ENTITIES].offset, 144);
}

TEST(BspRoundTrip, ForcedUnknownVersion) {
    Bsp bsp = makeSyntheticBsp();
    bsp.version = 48;
    const std::vector<uint8_t> image = serializeBsp(bsp);
    EXPECT_THROW(parseBsp(image, "v48.bsp"), BspError);
    ReadOptions force;
    force.force = true;
    Bsp back = parseBsp(image, "v48.bsp", force);
    EXPECT_EQ(back.version, 48);
    EXPECT_EQ(back.headerLumps, 17);
    expectSameLumps(bsp, back);
}

// Layouts written by other tools: q3map2's banner after an 18-entry header with empty lumps at the
// current position, older q3map2's banner after a 17-entry header, id's 17-entry layout in
// q3map2's lump order.
TEST(BspRoundTrip, ReadsLayoutsOfOtherCompilers) {
    const Bsp reference = makeSyntheticBsp();
    std::vector<std::vector<uint8_t>> lumps = allLumps(reference);
    const std::vector<int> q3map2Order = {1, 2, 4, 3, 8, 9, 5, 6, 7, 10, 13, 16, 14, 15, 0, 12, 11, 17};
    const std::string banner = "I LOVE MY Q3MAP2 2.5.17n on Sat Nov 21 2026";
    struct Layout {
        const char* what;
        int entries;
        std::string gap;
        int32_t emptyOffset;
    };
    const Layout layouts[] = {
        {"q3map2 18 entries with banner", 18, banner, -1},
        {"q3map2 17 entries with banner", 17, banner, -1},
        {"id 17 entries", 17, "", 0},
        {"18 entries, no gap", 18, "", 0},
    };
    for (const Layout& layout : layouts) {
        std::vector<int> order = q3map2Order;
        if (layout.entries == 17) order.pop_back();
        const std::vector<uint8_t> image = buildRawImage(kVersionQ3, layout.entries, lumps, layout.gap, order,
                                                         layout.emptyOffset);
        Bsp bsp = parseBsp(image, layout.what);
        EXPECT_EQ(bsp.headerLumps, layout.entries) << layout.what;
        expectSameLumps(reference, bsp);
        // Rewriting keeps the entry count and is stable.
        const std::vector<uint8_t> rewritten = serializeBsp(bsp);
        EXPECT_EQ(rawEntries(rewritten, layout.entries)[LUMP_ENTITIES].offset, 8 + 8 * layout.entries);
        EXPECT_EQ(serializeBsp(parseBsp(rewritten, layout.what)), rewritten) << layout.what;
    }
}

TEST(BspRoundTrip, Quake47LayoutWithBannerIsRead) {
    Bsp reference = makeSyntheticBsp();
    reference.lump17.assign(128, 0x5a);
    std::vector<std::vector<uint8_t>> lumps = allLumps(reference);
    const std::vector<uint8_t> image = buildRawImage(
        kVersionQL, 18, lumps, "I LOVE MY Q3MAP2", {1, 2, 4, 3, 8, 9, 5, 6, 7, 10, 13, 16, 14, 15, 0, 12, 11, 17}, -1);
    Bsp bsp = parseBsp(image, "ql.bsp");
    EXPECT_EQ(bsp.headerLumps, 18);
    EXPECT_EQ(bsp.lump17, reference.lump17);
    expectSameLumps(reference, bsp);
}

TEST(BspRoundTrip, EmptyBspRoundTrips) {
    Bsp empty;
    std::vector<uint8_t> image = serializeBsp(empty);
    EXPECT_EQ(image.size(), 144u);
    Bsp back = parseBsp(image, "empty.bsp");
    EXPECT_EQ(back.headerLumps, 17);
    EXPECT_EQ(serializeBsp(back), image);
}

TEST(BspRoundTrip, SerializeIsDeterministic) {
    Bsp bsp = makeSyntheticBsp();
    bsp.setBspx("FOO", {1, 2, 3});
    EXPECT_EQ(serializeBsp(bsp), serializeBsp(bsp));
}

TEST(BspRoundTrip, LumpsArePaddedWithZeros) {
    Bsp bsp = makeSyntheticBsp();
    bsp.entities = std::string("{\n\"classname\" \"worldspawn\"\n}\n") + '\0';  // 30 bytes: needs 2 padding bytes
    ASSERT_NE(bsp.entities.size() % 4, 0u);
    const std::vector<uint8_t> image = serializeBsp(bsp);
    const RawEntry e = rawEntries(image, 17)[LUMP_ENTITIES];
    for (size_t i = e.offset + e.length; i < ((e.offset + e.length + 3u) & ~3u); ++i) EXPECT_EQ(image[i], 0);
    roundTrip(bsp);
}

// BSPX ---------------------------------------------------------------------------------------------

size_t expectedTrailerOffset(const std::vector<uint8_t>& image, int entries) {
    size_t end = 8 + 8 * static_cast<size_t>(entries);
    for (const RawEntry& e : rawEntries(image, entries))
        end = std::max(end, static_cast<size_t>(e.offset) + static_cast<size_t>(e.length));
    return (end + 3) & ~size_t(3);
}

TEST(Bspx, LumpsRoundTripAndAreFound) {
    Bsp bsp = makeSyntheticBsp();
    bsp.entities.push_back('x');  // odd-sized last region so the trailer position needs rounding
    bsp.setBspx(sh::kBspxLumpName, makeShGridLump(2, 2, 1));
    bsp.setBspx("ODDSIZE", {1, 2, 3, 4, 5});
    bsp.setBspx("EMPTY", {});
    bsp.setBspx("DECOUPLED_LM", std::vector<uint8_t>(64, 9));
    std::vector<uint8_t> image;
    Bsp back = roundTrip(bsp, &image);

    ASSERT_NE(back.findBspx("ODDSIZE"), nullptr);
    EXPECT_EQ(back.findBspx("ODDSIZE")->data, (std::vector<uint8_t>{1, 2, 3, 4, 5}));
    EXPECT_EQ(back.findBspx("MISSING"), nullptr);
    ASSERT_EQ(back.bspx.size(), 4u);
    EXPECT_EQ(back.bspx[0].name, sh::kBspxLumpName);
    EXPECT_EQ(back.bspx[2].name, "EMPTY");

    // Independent look at the trailer: "BSPX" right after the last lump, file offsets, aligned.
    const size_t at = expectedTrailerOffset(image, 17);
    ASSERT_LE(at + 8, image.size());
    EXPECT_EQ(std::memcmp(image.data() + at, "BSPX", 4), 0);
    uint32_t count;
    std::memcpy(&count, image.data() + at + 4, 4);
    EXPECT_EQ(count, 4u);
    for (uint32_t i = 0; i < count; ++i) {
        const uint8_t* entry = image.data() + at + 8 + 32 * i;
        uint32_t offset, length;
        std::memcpy(&offset, entry + 24, 4);
        std::memcpy(&length, entry + 28, 4);
        const std::string name(reinterpret_cast<const char*>(entry));
        EXPECT_EQ(name, bsp.bspx[i].name);
        EXPECT_EQ(length, bsp.bspx[i].data.size());
        if (length == 0) {
            EXPECT_EQ(offset, 0u);
            continue;
        }
        EXPECT_EQ(offset % 4, 0u);
        EXPECT_GE(offset, at + 8 + 32 * count);
        ASSERT_LE(offset + length, image.size());
        EXPECT_EQ(std::vector<uint8_t>(image.begin() + offset, image.begin() + offset + length), bsp.bspx[i].data);
    }
}

TEST(Bspx, TrailerAfterVersion47SHFile) {
    Bsp bsp = makeSyntheticBsp();
    attachShGrid(bsp, makeShGridLump(1, 1, 1));
    bsp.setBspx("RGBLIGHTING", std::vector<uint8_t>(30, 7));
    std::vector<uint8_t> image;
    roundTrip(bsp, &image);
    EXPECT_EQ(std::memcmp(image.data() + expectedTrailerOffset(image, 19), "BSPX", 4), 0);
}

TEST(Bspx, SetReplacesAndRemoveDeletes) {
    Bsp bsp;
    bsp.setBspx("A", {1});
    bsp.setBspx("B", {2});
    bsp.setBspx("A", {3, 3});
    ASSERT_EQ(bsp.bspx.size(), 2u);
    EXPECT_EQ(bsp.bspx[0].name, "A");
    EXPECT_EQ(bsp.bspx[0].data, (std::vector<uint8_t>{3, 3}));
    EXPECT_TRUE(bsp.removeBspx("A"));
    EXPECT_FALSE(bsp.removeBspx("A"));
    ASSERT_EQ(bsp.bspx.size(), 1u);
    EXPECT_EQ(bsp.bspx[0].name, "B");
}

TEST(Bspx, TrailingBytesThatAreNotBspxAreIgnored) {
    Bsp bsp = makeSyntheticBsp();
    std::vector<uint8_t> image = serializeBsp(bsp);
    const std::string junk = "NOTBSPX trailing junk";
    image.insert(image.end(), junk.begin(), junk.end());
    Bsp back = parseBsp(image, "junk.bsp");
    EXPECT_TRUE(back.bspx.empty());
    expectSameLumps(bsp, back);
}

TEST(Bspx, NameOfTwentyThreeCharactersIsAccepted) {
    Bsp bsp = makeSyntheticBsp();
    const std::string longest(23, 'N');
    bsp.setBspx(longest, {1, 2, 3, 4});
    Bsp back = roundTrip(bsp);
    ASSERT_NE(back.findBspx(longest), nullptr);
}

// Files ----------------------------------------------------------------------------------------------

// readBsp gives the SH grid the file's own buffer (lump 18, or else the BSPX lump LIGHTGRID_SH)
// instead of a copy beside the whole file: the BSP reads back as parseBsp reads it, and the grid's
// buffer has the capacity of the file. Lumps around it keep their bytes and their order.
TEST(BspFile, ReadBspHandsTheFileBufferToTheShGrid) {
    const std::filesystem::path path = q3::test::tempDir() / "sh.bsp";
    for (const int form : {18, 1, 2}) {  // lump 18; BSPX alone; BSPX with lump 18 beside it
        Bsp bsp = makeSyntheticBsp();
        bsp.setBspx("BEFORE", {1, 2, 3});
        if (form != 1) attachShGrid(bsp, makeShGridLump(3, 2, 2));
        if (form != 18) bsp.setBspx(sh::kBspxLumpName, makeShGridLump(2, 2, 1));
        bsp.setBspx("AFTER", {4, 5, 6, 7, 8});
        writeBsp(path, bsp);
        const std::vector<uint8_t> image = readFileBytes(path);
        const Bsp back = readBsp(path);
        expectSameLumps(parseBsp(image, "sh.bsp"), back);
        expectSameLumps(bsp, back);
        EXPECT_EQ(serializeBsp(back), image) << "form " << form;
        const std::vector<uint8_t>& owner = form == 1 ? back.findBspx(sh::kBspxLumpName)->data : back.shGrid;
        EXPECT_EQ(owner.capacity(), image.size()) << "form " << form;
        if (form == 2) EXPECT_EQ(back.findBspx(sh::kBspxLumpName)->data.capacity(), 40u + 108u * 4u);
    }
}

TEST(BspFile, WriteThenReadGivesTheSameBsp) {
    const std::filesystem::path dir = q3::test::tempDir();
    const std::filesystem::path path = dir / "out.bsp";
    Bsp bsp = makeSyntheticBsp();
    attachShGrid(bsp, makeShGridLump(2, 1, 1));
    writeBsp(path, bsp);
    const std::vector<uint8_t> written = readFileBytes(path);
    EXPECT_EQ(written, serializeBsp(bsp));
    Bsp back = readBsp(path);
    expectSameLumps(bsp, back);
    // Overwriting replaces the file atomically and leaves no temporaries behind.
    bsp.setBspx("EXTRA", {4, 5, 6, 7});
    writeBsp(path, bsp);
    EXPECT_EQ(readFileBytes(path), serializeBsp(bsp));
    EXPECT_EQ(removeStaleTemporaries(path), 0);
    size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 1u);
}

TEST(BspFile, ReadingDoesNotModifyTheInput) {
    const std::filesystem::path path = q3::test::tempDir() / "in.bsp";
    writeBsp(path, makeSyntheticBsp());
    const std::vector<uint8_t> before = readFileBytes(path);
    const auto stamp = std::filesystem::last_write_time(path);
    (void)readBsp(path);
    EXPECT_EQ(readFileBytes(path), before);
    EXPECT_EQ(std::filesystem::last_write_time(path), stamp);
}

TEST(BspFile, MissingFileIsAFileError) {
    EXPECT_THROW(readBsp(q3::test::tempDir() / "absent.bsp"), FileError);
}

TEST(BspLumps, NamesAndRecordSizes) {
    EXPECT_EQ(lumpName(LUMP_DRAWVERTS), "drawverts");
    EXPECT_EQ(lumpName(LUMP_LIGHTGRID_SH), "lightgrid_sh");
    EXPECT_EQ(lumpRecordSize(LUMP_SURFACES), 104u);
    EXPECT_EQ(lumpRecordSize(LUMP_ENTITIES), 0u);
    EXPECT_EQ(lumpRecordSize(LUMP_LIGHTGRID), 8u);
    EXPECT_THROW(lumpBytes(Bsp{}, kMaxLumps), BspError);
    EXPECT_THROW(lumpBytes(Bsp{}, -1), BspError);
}

}  // namespace
}  // namespace q3::bsp::test
