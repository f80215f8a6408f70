// Post-processing of raw lightmap luxels in float units: the per-light box filter, the final fill of
// unmapped luxels from their neighbours, and the averaging of super-samples into BSP luxels, with
// q3map2's weights and rules.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "vec3.h"

namespace q3::light {

enum class LuxelState : uint8_t {
    Unmapped,  // no surface under it
    Occluded,  // on the surface but its sample point is inside solid
    Mapped,    // lit normally
    Flooded,   // was unmapped/occluded, filled from neighbours
};

// A luxel image (super-sampled or not) with the state of every luxel, row-major.
struct LuxelImage {
    int width = 0, height = 0;
    std::vector<Vec3> color;
    std::vector<LuxelState> state;

    LuxelImage() = default;
    LuxelImage(int w, int h, LuxelState initial = LuxelState::Unmapped)
        : width(w), height(h), color(size_t(w) * h), state(size_t(w) * h, initial) {}
    size_t index(int x, int y) const { return size_t(y) * width + x; }
};

// Radius in super luxels of the box filter: int(superSample * radius / sampleSize), at least 1 when
// a radius is set or -filter is on. `worldRadius` is the larger of the surface's
// q3map_lightmapFilterRadius and the light's _filterradius (negative counts as 0).
int luxelFilterRadius(float worldRadius, int sampleSize, int superSample, bool filterOption);

// A rectangle of luxels, [x0, x1] x [y0, y1]; empty when x1 < x0.
struct LuxelRect {
    int x0 = 0, x1 = -1, y0 = 0, y1 = -1;

    bool empty() const { return x1 < x0; }
    // Grows the rectangle to hold luxel (x, y).
    void add(int x, int y) {
        if (empty()) {
            *this = LuxelRect{x, x, y, y};
            return;
        }
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
};

// q3map2's per-light filter: every Mapped luxel becomes the weighted mean of the Mapped luxels in the
// (2r+1)^2 square around it, weight 1 inside and 0.5 per axis on the square's border. Other luxels
// are left unchanged. radius <= 0 returns the input. Only the rectangle around the lit Mapped
// luxels is visited: elsewhere every mean is of zeros. `nonzero`, when given, receives a rectangle
// outside which every luxel of the result is zero.
LuxelImage boxFilterLuxels(const LuxelImage& light, int radius, LuxelRect* nonzero = nullptr);
// The same for a light whose luxels outside `within` are all zero, visiting only the rectangles
// around its lit ones (radius > 0): returns the rectangle outside which every filtered luxel is
// zero, and writes the filtered colours inside it to `out` (resized to the image; the rest of it
// is left as it was).
LuxelRect boxFilterLuxelsWithin(const LuxelImage& light, int radius, LuxelRect within, std::vector<Vec3>& out);

// The final neighbour fill: each Unmapped or Occluded luxel (and, with splotchFix, each luxel with a
// channel at or below the ambient) takes the mean of its Mapped 3x3 neighbours (neighbours equal to
// the ambient are skipped with splotchFix) and becomes Flooded. With `dark` (-dark) the ambient is
// added twice into the mean to darken seams. Luxels with no usable neighbour stay as they were.
void fillFromNeighbours(LuxelImage& image, Vec3 ambient, bool dark, bool splotchFix);

// BSP luxels after averaging super-samples; `used` is false for luxels nothing reached.
struct BspLuxels {
    int width = 0, height = 0;
    std::vector<Vec3> color;
    std::vector<uint8_t> used;
};

// q3map2 StoreSurfaceLightmaps' averaging: each BSP luxel is the mean of its Mapped/Flooded
// super-samples, else of its Occluded ones; luxels with only Unmapped samples then borrow the mean of
// their non-empty 3x3 neighbours (or stay unused); negative channels clamp to 0.
BspLuxels downsampleSuperLuxels(const LuxelImage& super, int superSample);

}  // namespace q3::light
