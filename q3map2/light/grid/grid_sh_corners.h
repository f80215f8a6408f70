// The SH grid's default trace: blocks between corner points about 128 units apart per axis (4 x 4
// x 2 cells of the default SH grid), each corner point shared with the neighbouring blocks. Every
// corner point is lit once, with every light, and keeps per light whether its shadow ray was open
// or blocked and its light there. A block reads its corners light by light. They agree on a
// light when every corner's cluster may see it and the corners it reaches were all reached with a
// ray, all of them open or all blocked (a corner it does not reach holds none of its light). A far
// light (farFromBlock) the corners agree on is interpolated from them; a near one that reaches
// every corner is left out when blocked at all of them, and lit at every point without rays when
// open at all; any other light is lit and traced at every point. Occluders smaller than a block
// can hide from its corners: tests/lightsh/shared_light_test.cpp measures what that costs against
// every pair lit (-shexact).
// On the default grid one point in 32 is a corner, lit with every light, instead of one in 8 in
// blocks of their own. Corner planes are lit one z-slab ahead of the blocks that read them, so
// only two planes of corner records are held at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>

#include "grid_blocks.h"
#include "sh.h"

namespace q3 {
class Progress;
}

namespace q3::light {

struct ShPointSink {
    // Where point `index` (lattice position `lattice`) is lit; nullopt: in solid. Called once per point.
    std::function<std::optional<PlacedGridPoint>(size_t index, Vec3 lattice)> place;
    // The point's light (SH units, before ambient and -gridscale). Called once per free point.
    std::function<void(size_t index, sh::SH9Color& light)> store;
};

// Lights every point of `grid` (index x + y bx + z bx by) with the style-0 lights of `lights` not
// marked in `leftOut`; `envelopes` holds lightEnvelope of every light, `margin` how far a point may
// be nudged, `solidTree` (may be null) lets rays known clear of structural solid skip that walk.
// Returns the number of (light, point) pairs taken from the corners or left out.
uint64_t traceGridSHSharedCorners(const GridLattice& grid, std::span<const Light> lights,
                                  std::span<const uint8_t> leftOut, std::span<const float> envelopes,
                                  const LightingEnv& env, float margin, const BspTree* solidTree, int threads,
                                  Progress& progress, const ShPointSink& sink);

}  // namespace q3::light
