#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>

#include "lightmap_filter.h"

namespace q3::light {
namespace {

LuxelImage uniform(int w, int h, Vec3 c) {
    LuxelImage img(w, h, LuxelState::Mapped);
    for (Vec3& v : img.color) v = c;
    return img;
}

TEST(LightmapFilter, FilterRadiusInLuxels) {
    EXPECT_EQ(luxelFilterRadius(32, 16, 1, false), 2);
    EXPECT_EQ(luxelFilterRadius(48, 16, 2, false), 6);
    EXPECT_EQ(luxelFilterRadius(8, 16, 1, false), 1);  // int(0.5) = 0, but a radius was asked for
    EXPECT_EQ(luxelFilterRadius(0, 16, 2, true), 1);   // -filter alone
    EXPECT_EQ(luxelFilterRadius(0, 16, 2, false), 0);
    EXPECT_EQ(luxelFilterRadius(-5, 16, 2, false), 0);
}

TEST(LightmapFilter, BoxFilterWeights) {
    LuxelImage img = uniform(3, 3, {0, 0, 0});
    img.color[img.index(1, 1)] = {9, 18, 0};
    const LuxelImage f = boxFilterLuxels(img, 1);
    // Centre: weights 1 (itself), 0.5 x 4 edges, 0.25 x 4 corners = 4.
    EXPECT_FLOAT_EQ(f.color[f.index(1, 1)].x, 9.0f / 4.0f);
    EXPECT_FLOAT_EQ(f.color[f.index(1, 1)].y, 18.0f / 4.0f);
    // Corner (0,0): itself 1, (1,0) and (0,1) 0.5, (1,1) 0.25 -> 0.25*9 / 2.25.
    EXPECT_FLOAT_EQ(f.color[f.index(0, 0)].x, 1.0f);
    // Edge (1,0): itself 1, (0,0),(2,0) 0.5, (1,1) 0.5, (0,1),(2,1) 0.25 -> 0.5*9 / 3.
    EXPECT_FLOAT_EQ(f.color[f.index(1, 0)].x, 1.5f);
    // Radius 0 changes nothing.
    EXPECT_EQ(boxFilterLuxels(img, 0).color, img.color);
}

TEST(LightmapFilter, BoxFilterIgnoresUnmappedLuxels) {
    LuxelImage img = uniform(3, 1, {10, 10, 10});
    img.color[2] = {100, 100, 100};
    img.state[2] = LuxelState::Unmapped;
    const LuxelImage f = boxFilterLuxels(img, 1);
    EXPECT_FLOAT_EQ(f.color[1].x, 10.0f);     // the unmapped neighbour does not bleed in
    EXPECT_FLOAT_EQ(f.color[2].x, 100.0f);    // and is itself left alone
    EXPECT_EQ(f.state[2], LuxelState::Unmapped);
}

TEST(LightmapFilter, BoxFilterWithinARectangleMatchesTheWholeImage) {
    // A light that is zero outside one rectangle: filtering only around it gives the same luxels.
    for (const int radius : {1, 2, 3}) {
        LuxelImage img = uniform(20, 15, {0, 0, 0});
        unsigned seed = 5;
        auto next = [&seed] { return (seed = seed * 1103515245u + 12345u) >> 16; };
        const LuxelRect lit{5, 9, 3, 7};
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const size_t i = img.index(x, y);
                if (next() % 5 == 0) img.state[i] = LuxelState::Unmapped;
                const bool inside = x >= lit.x0 && x <= lit.x1 && y >= lit.y0 && y <= lit.y1;
                if (inside && next() % 3 != 0) img.color[i] = {float(next() % 100), float(next() % 7), 1};
            }
        LuxelRect whole;
        const LuxelImage f = boxFilterLuxels(img, radius, &whole);
        std::vector<Vec3> within(img.color.size(), Vec3{-1, -1, -1});
        const LuxelRect rect = boxFilterLuxelsWithin(img, radius, lit, within);
        EXPECT_EQ(rect.x0, whole.x0);
        EXPECT_EQ(rect.x1, whole.x1);
        EXPECT_EQ(rect.y0, whole.y0);
        EXPECT_EQ(rect.y1, whole.y1);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const size_t i = img.index(x, y);
                if (x >= rect.x0 && x <= rect.x1 && y >= rect.y0 && y <= rect.y1)
                    EXPECT_EQ(within[i], f.color[i]) << x << "," << y;
                else
                    EXPECT_EQ(f.color[i], (Vec3{})) << x << "," << y;
            }
    }
}

// The filter as its definition reads, one luxel at a time: the weighted mean of the Mapped luxels
// of the square, summed row by row, left to right.
Vec3 plainBoxFilter(const LuxelImage& img, int radius, int x, int y) {
    Vec3 sum;
    float weightSum = 0;
    for (int sy = std::max(0, y - radius); sy <= std::min(img.height - 1, y + radius); ++sy)
        for (int sx = std::max(0, x - radius); sx <= std::min(img.width - 1, x + radius); ++sx) {
            if (img.state[img.index(sx, sy)] != LuxelState::Mapped) continue;
            const float weight =
                (std::abs(sx - x) == radius ? 0.5f : 1.0f) * (std::abs(sy - y) == radius ? 0.5f : 1.0f);
            sum += img.color[img.index(sx, sy)] * weight;
            weightSum += weight;
        }
    return weightSum > 0 ? sum / weightSum : img.color[img.index(x, y)];
}

TEST(LightmapFilter, EveryLuxelIsThePlainFiltersToTheBit) {
    // Widths around the four-luxel blocks and the radius, colours with full mantissas: luxels
    // filtered four at a time must sum in the plain order, or their last bits differ.
    unsigned seed = 11;
    auto next = [&seed] { return (seed = seed * 1103515245u + 12345u) >> 8; };
    for (const int radius : {1, 2, 3})
        for (const int width : {1, 3, 4, 5, 7, 8, 9, 12, 13, 19}) {
            LuxelImage img(width, 6, LuxelState::Mapped);
            for (size_t i = 0; i < img.color.size(); ++i) {
                if (next() % 4 == 0) img.state[i] = next() % 2 ? LuxelState::Unmapped : LuxelState::Occluded;
                img.color[i] = {float(next() % 100000) / 7.0f, float(next() % 1000) / 3.0f, float(next() % 77) * 0.1f};
            }
            const LuxelImage f = boxFilterLuxels(img, radius);
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    const size_t i = img.index(x, y);
                    const Vec3 want =
                        img.state[i] == LuxelState::Mapped ? plainBoxFilter(img, radius, x, y) : img.color[i];
                    using Bits = std::array<uint32_t, 3>;
                    EXPECT_EQ(std::bit_cast<Bits>(f.color[i]), std::bit_cast<Bits>(want))
                        << "radius " << radius << " width " << width << " at " << x << "," << y;
                }
        }
}

TEST(LightmapFilter, FillFromNeighbours) {
    LuxelImage img = uniform(3, 3, {0, 0, 0});
    for (int i = 0; i < 9; ++i) img.color[size_t(i)] = {float(i), 0, 0};
    img.state[4] = LuxelState::Unmapped;
    img.state[0] = LuxelState::Occluded;
    LuxelImage plain = img;
    fillFromNeighbours(plain, {0, 0, 0}, false, false);
    // Centre: mapped neighbours 1,2,3,5,6,7,8 (0 is occluded) -> 32/7.
    EXPECT_FLOAT_EQ(plain.color[4].x, 32.0f / 7.0f);
    EXPECT_EQ(plain.state[4], LuxelState::Flooded);
    // Corner 0: mapped neighbours 1 and 3 (4 was unmapped before the pass) -> 2.
    EXPECT_FLOAT_EQ(plain.color[0].x, 2.0f);
    EXPECT_EQ(plain.state[0], LuxelState::Flooded);
    EXPECT_FLOAT_EQ(plain.color[8].x, 8.0f);  // mapped luxels untouched

    LuxelImage dark = img;
    fillFromNeighbours(dark, {7, 0, 0}, true, false);
    EXPECT_FLOAT_EQ(dark.color[4].x, (32.0f + 14.0f) / 9.0f);

    // Isolated unmapped luxel stays unmapped.
    LuxelImage lonely(1, 1, LuxelState::Unmapped);
    fillFromNeighbours(lonely, {}, false, false);
    EXPECT_EQ(lonely.state[0], LuxelState::Unmapped);
}

TEST(LightmapFilter, SplotchFix) {
    LuxelImage img = uniform(3, 1, {50, 50, 50});
    img.color[1] = {5, 60, 60};  // one channel at or below the ambient: a splotch
    img.color[2] = {10, 10, 10};  // equal to the ambient: skipped as a source
    fillFromNeighbours(img, {10, 10, 10}, false, true);
    EXPECT_FLOAT_EQ(img.color[1].x, 50.0f);
    EXPECT_EQ(img.state[1], LuxelState::Mapped);
    // Luxel 2 is itself at the ambient: refilled from luxel 1's old splotch value.
    EXPECT_FLOAT_EQ(img.color[2].x, 5.0f);
}

TEST(LightmapFilter, DownsampleSuperLuxels) {
    LuxelImage s(4, 4, LuxelState::Unmapped);
    auto set = [&](int x, int y, LuxelState st, Vec3 c) {
        s.state[s.index(x, y)] = st;
        s.color[s.index(x, y)] = c;
    };
    // Block (0,0): two lit samples and one occluded -> mean of the lit ones.
    set(0, 0, LuxelState::Mapped, {10, 20, 30});
    set(1, 0, LuxelState::Flooded, {30, 20, 10});
    set(0, 1, LuxelState::Occluded, {1000, 0, 0});
    // Block (1,0): occluded only -> their mean, negative clamped.
    set(2, 0, LuxelState::Occluded, {4, -8, 0});
    set(3, 1, LuxelState::Occluded, {8, -8, 0});
    // Block (0,1): nothing; block (1,1): one lit sample.
    set(3, 3, LuxelState::Mapped, {90, 90, 90});
    const BspLuxels b = downsampleSuperLuxels(s, 2);
    ASSERT_EQ(b.width, 2);
    ASSERT_EQ(b.height, 2);
    EXPECT_EQ(b.color[0], (Vec3{20, 20, 20}));
    EXPECT_EQ(b.color[1], (Vec3{6, 0, 0}));
    EXPECT_EQ(b.color[3], (Vec3{90, 90, 90}));
    // The empty block borrows the mean of its three neighbours (before clamping of block 1: -8).
    EXPECT_EQ(b.used[2], 1);
    EXPECT_NEAR(b.color[2].x, (20 + 6 + 90) / 3.0f, 1e-4f);
    EXPECT_NEAR(b.color[2].y, (20 - 8 + 90) / 3.0f, 1e-4f);
    // All empty: stays unused.
    const BspLuxels none = downsampleSuperLuxels(LuxelImage(2, 2), 2);
    EXPECT_EQ(none.used[0], 0);
}

}  // namespace
}  // namespace q3::light
