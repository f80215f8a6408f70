// misc_model autoclip (q3map2 model.cpp ClipModel), the default mode: spawnflag 2 alone, or a
// shader with q3map_clipModel and no autoclip spawnflag. Each triangle of a model surface whose
// shader is solid (or q3map_clipModel) becomes a detail brush: the triangle's plane, three side
// planes along the nearest axis and a back plane clipDepth behind, with q3map2's snapping of
// nearly axial planes. The other autoclip modes are refused with a warning naming the entity.
#pragma once

#include <string>
#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "draw_surface.h"

namespace q3::bspstage {

struct ClipOptions {
    float clipDepth = 2;     // -clipdepth, misc_model _clipdepth; negative: q3map2 uses 2
    bool debugClip = false;  // -debugclip: the brushes get shaders debugclip2 (front) and debugclip
    int bevelSnap = 0;       // -snap
};

inline constexpr int kClipModelFlag = 2;
// Every autoclip spawnflag (q3map2 eClipFlags): clip model, extrusions, pyramids, backplanes.
inline constexpr int kAutoclipFlags = 2 | 8 | 16 | 128 | 256 | 512 | 1024 | 2048 | 4096;

// Whether these spawnflags and shader ask for the default clip mode.
bool wantsDefaultClip(int spawnFlags, const ShaderInfo& shader);

struct ClipBrushes {
    std::vector<Brush> brushes;         // in the order made
    std::vector<std::string> warnings;  // q3map2's, for triangles that give no brush
};

// The clip brushes of one surface's triangles. `debugShaders`: with -debugclip, the front side's and
// the other sides' shaders (debugclip2, debugclip); nullptr otherwise.
ClipBrushes clipBrushesForSurface(const DrawSurface& ds, const ShaderInfo& shader, int mapEntityNum, float clipDepth,
                                  const ClipOptions& options, const ShaderInfo* (*debugShaders)[2],
                                  const std::string& modelName, PlaneSet& planes);

// Puts `clip` (in the order made) in front of the entity's brushes, last made first, as q3map2's
// list does, and renumbers what already names the entity's brushes: surfaces' brush and the leaf
// brush lists of `tree`.
void prependClipBrushes(BspEntity& e, std::vector<Brush> clip, std::vector<DrawSurface>& surfaces, Tree& tree);

}  // namespace q3::bspstage
