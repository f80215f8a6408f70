// Grouping of surfaces into shared raw lightmaps, as q3map2's SetupSurfaceLightmaps does: coplanar
// surfaces with the same projection and lighting attributes whose bounds touch get one lightmap.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "lightmap_layout.h"

namespace q3::light {

// Attributes that must match for surfaces to share a raw lightmap (besides axis, sample size and
// plane), and the keys q3map2 sorts by.
struct LightmapMergeTraits {
    int model = 0;              // BSP model (surfaces of different models never share)
    std::string shader;         // sort key
    int entity = 0;             // .srf entity
    int receiveShadows = 1;     // .srf receiveShadows
    float brightness = 1.0f;    // q3map_lightmapBrightness
    float filterRadius = 0.0f;  // q3map_lightmapFilterRadius
    bool splotchFix = false;    // q3map_splotchFix
    bool mergeable = false;     // q3map_lightmapMergable: non-coplanar surfaces may share too
};

struct SurfaceLightmapInput {
    SurfaceGeometry geometry;
    SurfaceLightmapParams params;
    LightmapMergeTraits traits;
};

// Groups of input indices (into `inputs`), in q3map2's order: inputs sorted by model (descending),
// shader, sample size, axis, plane and position, then each group grown greedily with every later
// input that matches and whose bounds touch the group's. Curved patches stay alone.
std::vector<std::vector<size_t>> groupSurfacesForLightmaps(std::span<const SurfaceLightmapInput> inputs);

// groupSurfacesForLightmaps + layoutSurfaceGroup for every group (groups that cannot be laid out are
// dropped with the layout's warning).
std::vector<RawLightmap> layoutMergedLightmaps(std::span<const SurfaceLightmapInput> inputs, const LayoutOptions& options,
                                               Log* log = nullptr);

}  // namespace q3::light
