#include "lightmap_filter.h"

#include <algorithm>
#include <bit>
#include <cstdlib>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace q3::light {
namespace {

#if !defined(__SSE2__)
// The box filter of one luxel (x, y) of `light`: the weighted mean of the Mapped luxels of its
// square, clamped to the image; false when the square has none.
bool filterOne(const LuxelImage& light, int radius, const float* weights, int x, int y, Vec3& mean) {
    const int side = 2 * radius + 1;
    const int sy0 = std::max(0, y - radius), sy1 = std::min(light.height - 1, y + radius);
    const int sx0 = std::max(0, x - radius), sx1 = std::min(light.width - 1, x + radius);
    Vec3 sum;
    float weightSum = 0.0f;
    for (int sy = sy0; sy <= sy1; ++sy) {
        const size_t row = light.index(0, sy);
        const float* weightRow = &weights[size_t(sy - y + radius) * size_t(side)];
        for (int sx = sx0; sx <= sx1; ++sx) {
            if (light.state[row + size_t(sx)] != LuxelState::Mapped) continue;
            const float weight = weightRow[sx - x + radius];
            sum += light.color[row + size_t(sx)] * weight;
            weightSum += weight;
        }
    }
    if (!(weightSum > 0.0f)) return false;
    mean = sum / weightSum;
    return true;
}
#endif

#if defined(__SSE2__)
// The luxels of a rectangle grown by the radius as planes of x, y and z and a mask (all bits set:
// Mapped), zero and masked off outside the image, with room for whole groups of four.
struct FilterPlanes {
    int x0 = 0, y0 = 0, stride = 0;  // image position of plane entry 0; entries per row
    std::vector<float> x, y, z, mask;
    size_t at(int ix, int iy) const { return size_t(iy - y0) * size_t(stride) + size_t(ix - x0); }
};

void fillPlanes(const LuxelImage& light, LuxelRect rect, int radius, FilterPlanes& p) {
    p.x0 = rect.x0 - radius;
    p.y0 = rect.y0 - radius;
    p.stride = (rect.x1 - rect.x0 + 1 + 3) / 4 * 4 + 2 * radius;
    const size_t size = size_t(p.stride) * size_t(rect.y1 - rect.y0 + 1 + 2 * radius);
    p.x.assign(size, 0.0f);
    p.y.assign(size, 0.0f);
    p.z.assign(size, 0.0f);
    p.mask.assign(size, 0.0f);
    const float all = std::bit_cast<float>(~0u);
    const int ix0 = std::max(0, p.x0), ix1 = std::min(light.width - 1, p.x0 + p.stride - 1);
    for (int iy = std::max(0, p.y0); iy <= std::min(light.height - 1, rect.y1 + radius); ++iy)
        for (int ix = ix0; ix <= ix1; ++ix) {
            const size_t i = light.index(ix, iy), o = p.at(ix, iy);
            if (light.state[i] != LuxelState::Mapped) continue;
            p.x[o] = light.color[i].x;
            p.y[o] = light.color[i].y;
            p.z[o] = light.color[i].z;
            p.mask[o] = all;
        }
}

// The box filter of luxels x .. x + 3 of row y: each lane sums the Mapped luxels of its square,
// weighted, row by row and left to right, as a plain loop over one luxel would. Taps outside the
// image or not Mapped add +0, which changes no sum (one that starts at +0 never becomes -0).
// Writes the lanes inside `rect` whose own luxel is Mapped.
void filterFour(const LuxelImage& light, const FilterPlanes& p, int radius, const float* weights, int x, int y,
                const LuxelRect& rect, std::vector<Vec3>& out) {
    const int side = 2 * radius + 1;
    __m128 sumX = _mm_setzero_ps(), sumY = _mm_setzero_ps(), sumZ = _mm_setzero_ps(), weightSum = _mm_setzero_ps();
    for (int dy = -radius; dy <= radius; ++dy) {
        const size_t row = p.at(x - radius, y + dy);
        const float* weightRow = &weights[size_t(dy + radius) * size_t(side)];
        for (int k = 0; k < side; ++k) {
            const __m128 use = _mm_loadu_ps(&p.mask[row + size_t(k)]);
            const __m128 w = _mm_set1_ps(weightRow[k]);
            sumX = _mm_add_ps(sumX, _mm_and_ps(use, _mm_mul_ps(_mm_loadu_ps(&p.x[row + size_t(k)]), w)));
            sumY = _mm_add_ps(sumY, _mm_and_ps(use, _mm_mul_ps(_mm_loadu_ps(&p.y[row + size_t(k)]), w)));
            sumZ = _mm_add_ps(sumZ, _mm_and_ps(use, _mm_mul_ps(_mm_loadu_ps(&p.z[row + size_t(k)]), w)));
            weightSum = _mm_add_ps(weightSum, _mm_and_ps(use, w));
        }
    }
    alignas(16) float mx[4], my[4], mz[4], ws[4];
    _mm_store_ps(mx, _mm_div_ps(sumX, weightSum));
    _mm_store_ps(my, _mm_div_ps(sumY, weightSum));
    _mm_store_ps(mz, _mm_div_ps(sumZ, weightSum));
    _mm_store_ps(ws, weightSum);
    for (int l = 0; l < 4 && x + l <= rect.x1; ++l) {
        const size_t i = light.index(x + l, y);
        if (light.state[i] == LuxelState::Mapped && ws[l] > 0.0f) out[i] = Vec3{mx[l], my[l], mz[l]};
    }
}
#endif

}  // namespace

int luxelFilterRadius(float worldRadius, int sampleSize, int superSample, bool filterOption) {
    const float radius = std::max(0.0f, worldRadius);
    int luxels = sampleSize != 0 ? int(float(superSample) * radius / float(sampleSize)) : 0;
    if (luxels == 0 && (radius > 0.0f || filterOption)) luxels = 1;
    return luxels;
}

LuxelRect boxFilterLuxelsWithin(const LuxelImage& light, int radius, LuxelRect within, std::vector<Vec3>& out) {
    // Only lit Mapped luxels feed the means: a luxel whose square holds none keeps its zero, so
    // only the rectangle around them, grown by the radius, needs filtering (a light usually
    // reaches a corner of a large lightmap, and this runs once a light). Each row is searched from
    // both ends for its first nonzero luxel and its first lit one.
    LuxelRect lit, any;
    // The first and last x in [from, to] where `holds` does; false when it holds nowhere.
    auto ends = [](int from, int to, auto holds, int& first, int& last) {
        for (first = from; first <= to && !holds(first);) ++first;
        if (first > to) return false;
        for (last = to; !holds(last);) --last;
        return true;
    };
    const int wx0 = std::max(0, within.x0), wx1 = std::min(light.width - 1, within.x1);
    for (int y = std::max(0, within.y0); y <= std::min(light.height - 1, within.y1); ++y) {
        const size_t row = light.index(0, y);
        auto nonzero = [&](int x) { return !(light.color[row + size_t(x)] == Vec3{}); };
        auto litAt = [&](int x) { return nonzero(x) && light.state[row + size_t(x)] == LuxelState::Mapped; };
        int first, last;
        if (!ends(wx0, wx1, nonzero, first, last)) continue;
        any.add(first, y);
        any.add(last, y);
        if (!ends(first, last, litAt, first, last)) continue;
        lit.add(first, y);
        lit.add(last, y);
    }
    if (!lit.empty()) {
        lit = LuxelRect{std::max(0, lit.x0 - radius), std::min(light.width - 1, lit.x1 + radius),
                        std::max(0, lit.y0 - radius), std::min(light.height - 1, lit.y1 + radius)};
        any.add(lit.x0, lit.y0);
        any.add(lit.x1, lit.y1);
    }
    out.resize(light.color.size());
    for (int y = any.y0; y <= any.y1; ++y)
        for (int x = any.x0; x <= any.x1; ++x) out[light.index(x, y)] = light.color[light.index(x, y)];
    // The border of the square counts half per axis (a quarter in the corners): weights by offset.
    const int side = 2 * radius + 1;
    thread_local std::vector<float> weights;
    weights.resize(size_t(side) * size_t(side));
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            weights[size_t(dy + radius) * size_t(side) + size_t(dx + radius)] =
                (std::abs(dx) == radius ? 0.5f : 1.0f) * (std::abs(dy) == radius ? 0.5f : 1.0f);
#if defined(__SSE2__)
    thread_local FilterPlanes planes;
    if (!lit.empty()) fillPlanes(light, lit, radius, planes);
    for (int y = lit.y0; y <= lit.y1; ++y)
        for (int x = lit.x0; x <= lit.x1; x += 4) filterFour(light, planes, radius, weights.data(), x, y, lit, out);
#else
    for (int y = lit.y0; y <= lit.y1; ++y)
        for (int x = lit.x0; x <= lit.x1; ++x)
            if (light.state[light.index(x, y)] == LuxelState::Mapped)
                filterOne(light, radius, weights.data(), x, y, out[light.index(x, y)]);
#endif
    return any;
}

LuxelImage boxFilterLuxels(const LuxelImage& light, int radius, LuxelRect* nonzero) {
    if (nonzero) *nonzero = LuxelRect{0, light.width - 1, 0, light.height - 1};
    if (radius <= 0) return light;
    LuxelImage out = light;
    std::vector<Vec3> filtered;
    const LuxelRect any =
        boxFilterLuxelsWithin(light, radius, LuxelRect{0, light.width - 1, 0, light.height - 1}, filtered);
    for (int y = any.y0; y <= any.y1; ++y)
        for (int x = any.x0; x <= any.x1; ++x) out.color[light.index(x, y)] = filtered[light.index(x, y)];
    if (nonzero) *nonzero = any;
    return out;
}

void fillFromNeighbours(LuxelImage& image, Vec3 ambient, bool dark, bool splotchFix) {
    // Reads only the luxels as they were before this pass, so the result does not depend on the
    // visiting order.
    const LuxelImage before = image;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const size_t i = image.index(x, y);
            const LuxelState state = before.state[i];
            const Vec3 c = before.color[i];
            const bool needsFill = state == LuxelState::Unmapped || state == LuxelState::Occluded ||
                                   (splotchFix && (c.x <= ambient.x || c.y <= ambient.y || c.z <= ambient.z));
            if (!needsFill) continue;
            Vec3 sum;
            float samples = 0.0f;
            for (int sy = std::max(0, y - 1); sy <= std::min(image.height - 1, y + 1); ++sy) {
                for (int sx = std::max(0, x - 1); sx <= std::min(image.width - 1, x + 1); ++sx) {
                    if (sx == x && sy == y) continue;
                    const size_t j = before.index(sx, sy);
                    if (before.state[j] != LuxelState::Mapped) continue;
                    if (splotchFix && before.color[j] == ambient) continue;
                    sum += before.color[j];
                    samples += 1.0f;
                }
            }
            if (samples <= 0.0f) continue;
            if (dark) {
                sum += ambient * 2.0f;
                samples += 2.0f;
            }
            image.color[i] = sum / samples;
            if (state != LuxelState::Mapped) image.state[i] = LuxelState::Flooded;
        }
    }
}

BspLuxels downsampleSuperLuxels(const LuxelImage& super, int superSample) {
    const int ss = std::max(1, superSample);
    BspLuxels out;
    out.width = super.width / ss;
    out.height = super.height / ss;
    out.color.assign(size_t(out.width) * out.height, Vec3{});
    out.used.assign(size_t(out.width) * out.height, 0);

    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            Vec3 lit, occluded;
            int litCount = 0, occludedCount = 0;
            for (int ly = 0; ly < ss; ++ly) {
                for (int lx = 0; lx < ss; ++lx) {
                    const size_t i = super.index(x * ss + lx, y * ss + ly);
                    switch (super.state[i]) {
                        case LuxelState::Mapped:
                        case LuxelState::Flooded: lit += super.color[i]; ++litCount; break;
                        case LuxelState::Occluded: occluded += super.color[i]; ++occludedCount; break;
                        case LuxelState::Unmapped: break;
                    }
                }
            }
            const size_t o = size_t(y) * out.width + x;
            // Occluded samples only count when nothing better exists.
            if (litCount > 0) {
                out.color[o] = lit / float(litCount);
                out.used[o] = 1;
            } else if (occludedCount > 0) {
                out.color[o] = occluded / float(occludedCount);
                out.used[o] = 1;
            }
        }
    }
    // Luxels nothing reached borrow from their used 3x3 neighbours (original values only).
    const std::vector<uint8_t> usedBefore = out.used;
    const std::vector<Vec3> colorBefore = out.color;
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const size_t o = size_t(y) * out.width + x;
            if (usedBefore[o]) continue;
            Vec3 sum;
            int count = 0;
            for (int sy = std::max(0, y - 1); sy <= std::min(out.height - 1, y + 1); ++sy)
                for (int sx = std::max(0, x - 1); sx <= std::min(out.width - 1, x + 1); ++sx) {
                    const size_t j = size_t(sy) * out.width + sx;
                    if (j == o || !usedBefore[j]) continue;
                    sum += colorBefore[j];
                    ++count;
                }
            if (count > 0) {
                out.color[o] = sum / float(count);
                out.used[o] = 1;
            }
        }
    }
    for (Vec3& c : out.color) c = vmax(c, Vec3{});
    return out;
}

}  // namespace q3::light
