// The SH grid lump codec: byte layout, round trip, and rejection of malformed lumps with one clear line.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "sh_grid_lump.h"
#include "sh_test_support.h"

namespace q3::sh {
namespace {

GridSH makeGrid(int bx, int by, int bz) {
    GridSH grid;
    const float mins[3] = {-128, 64.5f, -32};
    const float size[3] = {32, 32, 64};
    const int32_t bounds[3] = {bx, by, bz};
    for (int a = 0; a < 3; ++a) {
        grid.mins[a] = mins[a];
        grid.size[a] = size[a];
        grid.bounds[a] = bounds[a];
    }
    grid.points.resize(size_t(bx) * by * bz);
    for (size_t p = 0; p < grid.points.size(); ++p)
        for (int i = 0; i < 9; ++i)
            for (int c = 0; c < 3; ++c) grid.points[p].coeffs[i][c] = float(p) * 0.5f + i * 0.01f - c * 1.25f;
    return grid;
}

void expectOneLine(const std::string& error, const char* mentions) {
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_NE(error.find(mentions), std::string::npos) << error;
}

TEST(ShGridLump, LittleEndianLayout) {
    const GridSH grid = makeGrid(2, 1, 3);
    const std::vector<uint8_t> bytes = encodeGridLump(grid);
    ASSERT_EQ(bytes.size(), 40u + 108u * 6);
    // gridMins[0] = -128.0f = 0xC3000000, gridBounds[2] = 3, numPoints = 6.
    EXPECT_EQ(bytes[0], 0x00);
    EXPECT_EQ(bytes[3], 0xC3);
    EXPECT_EQ(bytes[32], 3);
    EXPECT_EQ(bytes[33], 0);
    EXPECT_EQ(bytes[36], 6);
    // Point 1, coefficient 2, channel 1 sits at 40 + 108 + (2*3 + 1) * 4.
    float value;
    const size_t at = 40 + 108 + (2 * 3 + 1) * 4;
    const uint32_t u = uint32_t(bytes[at]) | uint32_t(bytes[at + 1]) << 8 | uint32_t(bytes[at + 2]) << 16 |
                       uint32_t(bytes[at + 3]) << 24;
    std::memcpy(&value, &u, 4);
    EXPECT_EQ(value, grid.points[1].coeffs[2][1]);
}

TEST(ShGridLump, RoundTripIsBitExact) {
    const GridSH grid = makeGrid(3, 2, 4);
    const std::vector<uint8_t> bytes = encodeGridLump(grid);
    EXPECT_EQ(checkGridLump(bytes.data(), bytes.size()), "");
    GridSH back;
    std::string error;
    ASSERT_TRUE(decodeGridLump(bytes.data(), bytes.size(), back, error)) << error;
    EXPECT_TRUE(error.empty());
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(back.mins[a], grid.mins[a]);
        EXPECT_EQ(back.size[a], grid.size[a]);
        EXPECT_EQ(back.bounds[a], grid.bounds[a]);
    }
    ASSERT_EQ(back.points.size(), grid.points.size());
    EXPECT_EQ(std::memcmp(back.points.data(), grid.points.data(), grid.points.size() * sizeof(GridPointSH)), 0);
    EXPECT_EQ(encodeGridLump(back), bytes);
}

// Points set one by one into an image made from the lattice give the bytes of the whole-grid
// encoder; each point reads back bit-exact, and release() hands the buffer over and empties it.
TEST(ShGridLump, ImageFilledInPlaceMatchesTheEncoder) {
    const GridSH grid = makeGrid(3, 2, 4);
    GridLumpImage image(grid.mins, grid.size, grid.bounds);
    ASSERT_EQ(image.numPoints(), grid.points.size());
    EXPECT_EQ(image.bounds(), (std::array<int32_t, 3>{3, 2, 4}));
    EXPECT_EQ(checkGridLump(image.bytes().data(), image.bytes().size()), "") << "a fresh image is a valid all-zero grid";
    for (size_t i = grid.points.size(); i-- > 0;) image.setPoint(i, grid.points[i]);  // any order
    EXPECT_EQ(image.bytes(), encodeGridLump(grid));
    for (size_t i = 0; i < grid.points.size(); ++i) {
        const GridPointSH p = image.point(i);
        EXPECT_EQ(std::memcmp(&grid.points[i], &p, sizeof p), 0) << i;
    }
    const GridSH back = image.decode();
    EXPECT_EQ(std::memcmp(back.points.data(), grid.points.data(), grid.points.size() * sizeof(GridPointSH)), 0);
    const uint8_t* buffer = image.bytes().data();
    const std::vector<uint8_t> bytes = image.release();
    EXPECT_EQ(bytes.data(), buffer);
    EXPECT_EQ(bytes, encodeGridLump(grid));
    EXPECT_TRUE(image.bytes().empty());
    EXPECT_EQ(image.numPoints(), 0u);
}

TEST(ShGridLump, RejectsShortHeader) {
    const std::vector<uint8_t> bytes = encodeGridLump(makeGrid(1, 1, 1));
    expectOneLine(checkGridLump(bytes.data(), 39), "shorter than its 40-byte header");
    expectOneLine(checkGridLump(bytes.data(), 0), "header");
}

TEST(ShGridLump, RejectsWrongLength) {
    std::vector<uint8_t> bytes = encodeGridLump(makeGrid(2, 2, 2));
    expectOneLine(checkGridLump(bytes.data(), bytes.size() - 1), "length");
    bytes.push_back(0);
    expectOneLine(checkGridLump(bytes.data(), bytes.size()), "length");
    GridSH out;
    std::string error;
    EXPECT_FALSE(decodeGridLump(bytes.data(), bytes.size(), out, error));
    expectOneLine(error, "length");
}

TEST(ShGridLump, RejectsCountMismatch) {
    std::vector<uint8_t> bytes = encodeGridLump(makeGrid(2, 2, 2));
    test::putU32(bytes, 36, 7);
    expectOneLine(checkGridLump(bytes.data(), bytes.size()), "numPoints 7 != gridBounds product 8");
}

TEST(ShGridLump, RejectsBadBounds) {
    std::vector<uint8_t> bytes = encodeGridLump(makeGrid(2, 2, 2));
    test::putU32(bytes, 28, 0);
    expectOneLine(checkGridLump(bytes.data(), bytes.size()), "gridBounds y = 0");
    test::putU32(bytes, 28, uint32_t(-5));
    expectOneLine(checkGridLump(bytes.data(), bytes.size()), "gridBounds y = -5");
    // A product past 2^31 is refused before any size arithmetic can wrap.
    test::putU32(bytes, 24, 1 << 20);
    test::putU32(bytes, 28, 1 << 20);
    test::putU32(bytes, 32, 1 << 20);
    expectOneLine(checkGridLump(bytes.data(), bytes.size()), "2^31");
}

TEST(ShGridLump, RejectsNonFiniteValues) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<uint8_t> bytes = encodeGridLump(makeGrid(2, 1, 1));
    std::vector<uint8_t> bad = bytes;
    test::putF32(bad, 40 + 108 + 4 * 13, nan);  // point 1, coefficient 4, channel 1
    expectOneLine(checkGridLump(bad.data(), bad.size()), "point 1 coefficient 4 channel 1 is not finite");
    bad = bytes;
    test::putF32(bad, 4, inf);
    expectOneLine(checkGridLump(bad.data(), bad.size()), "gridMins y is not finite");
    bad = bytes;
    test::putF32(bad, 20, 0.0f);
    expectOneLine(checkGridLump(bad.data(), bad.size()), "gridSize z");
    bad = bytes;
    test::putF32(bad, 12, -4.0f);
    expectOneLine(checkGridLump(bad.data(), bad.size()), "gridSize x");
    bad = bytes;
    test::putF32(bad, 16, nan);
    expectOneLine(checkGridLump(bad.data(), bad.size()), "gridSize y");
}

TEST(ShGridLump, FailedDecodeLeavesOutputUntouched) {
    std::vector<uint8_t> bytes = encodeGridLump(makeGrid(1, 1, 2));
    GridSH out = makeGrid(1, 1, 1);
    std::string error;
    test::putU32(bytes, 36, 3);
    EXPECT_FALSE(decodeGridLump(bytes.data(), bytes.size(), out, error));
    EXPECT_EQ(out.points.size(), 1u);
}

}  // namespace
}  // namespace q3::sh
