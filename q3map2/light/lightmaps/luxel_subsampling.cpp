// q3map2's adaptive sub-sampling (luxel_subsampling.h).
#include "luxel_subsampling.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace q3::light {
namespace {

// Luxel flags of the sub-sampling walk.
constexpr uint8_t kNoPoint = 1, kDark = 2, kLit = 4;
constexpr size_t kFlagPadding = 16;  // room after the last row for the walk's eight-byte loads

}  // namespace

std::vector<uint8_t> darkFlagsOf(const std::vector<std::optional<SamplePoint>>& points) {
    std::vector<uint8_t> flags(points.size() + kFlagPadding);
    for (size_t i = 0; i < points.size(); ++i) flags[i] = points[i] ? kDark : kNoPoint;
    return flags;
}

void refineEdges(const LuxelSampler& sampler, const Light& light, const std::vector<std::optional<SamplePoint>>& points,
                 int w, int h, int maxSamples, std::vector<Vec3>& color, std::vector<int>& samples, LuxelRect& lit,
                 const std::vector<uint8_t>& darkFlags, LuxelSampler::Scratch& scratch, size_t minBatched) {
    if (lit.empty()) return;
    // Each luxel as a flag: kNoPoint, kDark or kLit. A window is refined only when it has both a
    // dark and a lit luxel, which the four flags tell; eight windows at a time from two rows of
    // flags (bytes are lanes: an or has no carries). A row's flags are made before the windows
    // reach it, from `darkFlags` (the flags of an unlit lightmap) and the lit luxels, which lie
    // in `lit` as it stands then, and follow the luxels the windows refine.
    // `darkFlags` tells which luxels have a point (reading the points themselves would walk a
    // far larger array).
    auto luxelState = [&](size_t i) -> uint8_t {
        if (darkFlags[i] == kNoPoint) return kNoPoint;
        return color[i].x + color[i].y + color[i].z > 0 ? kLit : kDark;
    };
    std::vector<uint8_t> state(points.size() + kFlagPadding);
    int madeRows = std::max(0, lit.y0 - 1);  // the rows from the first window's up to this one have flags
    auto makeRowsThrough = [&](int last) {
        for (; madeRows <= last && madeRows < h; ++madeRows) {
            const size_t row = size_t(madeRows) * size_t(w);
            std::memcpy(&state[row], &darkFlags[row], size_t(w));
            if (madeRows < lit.y0 || madeRows > lit.y1) continue;
            for (int x = lit.x0; x <= lit.x1; ++x) state[row + size_t(x)] = luxelState(row + size_t(x));
        }
    };
    // The first window from (x, y) on, up to `last`, with a dark and a lit luxel; -1 when none.
    auto nextMixed = [&](int x, int y, int last) {
        auto load = [&](size_t i) {
            uint64_t v;
            std::memcpy(&v, &state[i], sizeof v);
            return v;
        };
        for (; x <= last; x += 8) {
            const size_t top = size_t(y) * size_t(w) + size_t(x), bottom = top + size_t(w);
            const uint64_t any = load(top) | load(top + 1) | load(bottom) | load(bottom + 1);
            uint64_t mixed = (any << 1) & any & 0x0404040404040404ull;  // kDark shifted onto kLit
            if (last - x < 7) mixed &= (uint64_t(1) << (8 * (last - x + 1))) - 1;
            if (mixed) return x + std::countr_zero(mixed) / 8;
        }
        return -1;
    };
    // Whether the mixed window at (x, y) holds more than 4 in some channel.
    auto bright = [&](int x, int y) {
        Vec3 total;
        for (int t = 0; t < 4; ++t) {
            const size_t i = size_t(y + (t >> 1)) * size_t(w) + size_t(x + (t & 1));
            if (points[i]) total += color[i];
        }
        return maxComponent(total) > 4;
    };
    // Every stamp with a dark and a lit luxel and more than 4 in some channel, row by row, as it
    // stands when the walk reaches it (`visit` may refine its luxels and grow `lit`).
    auto forEachStampToRefine = [&](auto&& visit) {
        for (int y = std::max(0, lit.y0 - 1); y + 1 < h && y <= lit.y1; ++y) {
            makeRowsThrough(y + 1);
            for (int x = nextMixed(std::max(0, lit.x0 - 1), y, std::min(w - 2, lit.x1)); x >= 0;
                 x = nextMixed(x + 1, y, std::min(w - 2, lit.x1)))
                if (bright(x, y)) visit(x, y);
        }
    };
    std::vector<uint32_t> batched;  // luxels whose first quad is lit in advance, ascending
    forEachStampToRefine([&](int x, int y) {
        for (int t = 0; t < 4; ++t) {
            const uint32_t i = uint32_t(y + (t >> 1)) * uint32_t(w) + uint32_t(x + (t & 1));
            if (points[i]) batched.push_back(i);
        }
    });
    std::sort(batched.begin(), batched.end());
    batched.erase(std::unique(batched.begin(), batched.end()), batched.end());
    if (batched.size() < minBatched) batched.clear();
    std::vector<LuxelSampler::SubsampleQuad> quads;
    sampler.firstQuads(light, points, w, h, batched, quads, scratch);

    forEachStampToRefine([&](int x, int y) {
        for (int t = 0; t < 4; ++t) {
            const int lx = x + (t & 1), ly = y + (t >> 1);
            const size_t i = size_t(ly) * size_t(w) + size_t(lx);
            if (!points[i] || samples[i] >= maxSamples) continue;
            const auto it = std::lower_bound(batched.begin(), batched.end(), uint32_t(i));
            if (it != batched.end() && *it == i) {
                LuxelSampler::SubsampleQuad q = quads[size_t(it - batched.begin())];
                color[i] =
                    sampler.finishSubsample(light, points, w, h, lx, ly, q, 0.25f, samples[i], maxSamples, color[i]);
            } else {
                color[i] = sampler.subsample(light, points, w, h, lx, ly, points[i]->origin, 0.25f, samples[i],
                                             maxSamples, color[i]);
            }
            state[i] = luxelState(i);
            ++samples[i];
            lit.add(lx, ly);
        }
    });
    for (int y = lit.y0; y <= lit.y1; ++y)
        std::fill_n(samples.begin() + ptrdiff_t(y) * w + lit.x0, lit.x1 - lit.x0 + 1, 1);
}

}  // namespace q3::light
