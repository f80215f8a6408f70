// q3map2's adaptive sub-sampling of a light's luxels (-samples N): the walk over 2x2 stamps that
// refines the luxels at the light's edges.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "lightmap_filter.h"
#include "luxel_sampler.h"

namespace q3::light {

// The walk's flags of a lightmap that no light has reached yet (one byte per super luxel, and
// padding), made once per lightmap for every light's walk.
std::vector<uint8_t> darkFlagsOf(const std::vector<std::optional<SamplePoint>>& points);

// q3map2's adaptive sub-sampling (-samples N): a walk over every 2x2 stamp of the light's luxels,
// in rows; a stamp with lit and unlit luxels and more than 4 in some channel sub-samples each of its
// luxels that may still take a sample, in place, so later stamps see the refined values.
// `lit` holds every luxel of `color` that is not zero, and grows with the refined ones: a stamp
// outside it is all zeros when its turn comes, so the walk visits only the stamps that meet it
// (a light usually reaches a corner of a large lightmap, and this runs once a light). `samples`
// (all 1, as left by the previous call) counts each luxel's samples.
// A luxel's first quad of sub-samples does not depend on the walk (only what is made of it does),
// so the quads of the luxels that the stamps as they stand before the walk would refine are lit
// first, as one batch of rays (when there are `minBatched` such luxels or more: a few rays are
// traced faster one by one); a luxel that the walk reaches otherwise is sub-sampled on its own.
constexpr size_t kMinBatchedLuxels = 2;
void refineEdges(const LuxelSampler& sampler, const Light& light, const std::vector<std::optional<SamplePoint>>& points,
                 int w, int h, int maxSamples, std::vector<Vec3>& color, std::vector<int>& samples, LuxelRect& lit,
                 const std::vector<uint8_t>& darkFlags, LuxelSampler::Scratch& scratch,
                 size_t minBatched = kMinBatchedLuxels);

}  // namespace q3::light
