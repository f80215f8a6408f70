// misc_model autoclip (q3map2 model.cpp ClipModel): the triangles of a model's solid (or
// q3map_clipModel) surfaces become detail brushes. The spawnflags choose the shape:
//   2 alone, or a q3map_clipModel shader and no other flag: sides along the axis nearest the
//     polygon's normal, a back plane clipDepth behind;
//   8 sides along the face normal; 8+256 sides leaning out at 45 degrees; 256 a pyramid whose apex
//     lies clipDepth behind the centre; 256+4096 a pyramid with sides near the axes;
//   16 / 512 / 1024 / 512+1024 extruded along the model's main axis / down / up / the nearer of
//     up and down (a polygon facing away from it falls back to the default);
//   128 sides along the averaged vertex normals, 128+256 without the outward check;
//   4096, alone or with 16/512/1024, and 2048 with 16/512/1024: extruded along the axis nearest the
//     normal (or as above) to a back plane square to it, at the polygon's far corner (4096) or the
//     model's bounds (2048) plus clipDepth.
// Coplanar triangles sharing edges are merged into convex polygons first (clip_windings.h), and for
// the 4096/2048 shapes those polygons into convex volumes; 128 and 128+256 work triangle by
// triangle. Other combinations make no brushes: the caller warns about them.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "draw_surface.h"

namespace q3::bspstage {

struct ClipOptions {
    float clipDepth = 2;     // -clipdepth, misc_model _clipdepth; negative: 2, and its size limits some modes
    bool debugClip = false;  // -debugclip: the brushes get shaders debugclip2 (front) and debugclip
    int bevelSnap = 0;       // -snap
};

namespace clipflag {
inline constexpr int Model = 2;
inline constexpr int FaceNormals = 8;
inline constexpr int Terrain = 16;
inline constexpr int VertexNormals = 128;
inline constexpr int Pyramidal = 256;
inline constexpr int Downwards = 512;
inline constexpr int Upwards = 1024;
inline constexpr int MaxExtrude = 2048;
inline constexpr int AxialBackplane = 4096;
inline constexpr int All =
    Model | FaceNormals | Terrain | VertexNormals | Pyramidal | Downwards | Upwards | MaxExtrude | AxialBackplane;
}  // namespace clipflag

enum class ClipMode {
    None,        // no clip flag and no q3map_clipModel
    Unknown,     // flags that name no mode (q3map2: "nonexistent clipping mode selected")
    Merged,      // coplanar triangles merged, then one brush per polygon
    Volumetric,  // polygons merged further into volumes (the 4096 and 2048 shapes)
    PerTriangle  // vertex-normal modes
};

// The mode these spawnflags and this surface shader ask for.
ClipMode clipModeFor(int spawnFlags, const ShaderInfo& shader);

struct ClipBrushes {
    std::vector<Brush> brushes;         // in the order made
    std::vector<std::string> warnings;  // q3map2's, for polygons that give no brush
};

struct ClipRequest {
    int spawnFlags = 0;
    int mapEntityNum = 0;
    float clipDepth = 2;
    const std::string* modelName = nullptr;
    // With -debugclip, the front side's and the other sides' shaders (debugclip2, debugclip).
    const ShaderInfo* debugShaders[2] = {nullptr, nullptr};
};

struct ClipSurface {
    const DrawSurface* ds = nullptr;
    std::vector<DVec3> positions;  // ds's vertices placed in doubles (merged modes take these)
};

// The clip brushes of one model's surfaces (those with a mode and a solid or q3map_clipModel
// shader), made as q3map2 makes them.
ClipBrushes clipBrushesForModel(std::span<const ClipSurface> surfaces, const ClipRequest& request,
                                const ClipOptions& options, PlaneSet& planes);

// Puts `clip` (in the order made) in front of the entity's brushes, last made first, as q3map2's
// list does, and renumbers what already names the entity's brushes: surfaces' brush and the leaf
// brush lists of `tree`.
void prependClipBrushes(BspEntity& e, std::vector<Brush> clip, std::vector<DrawSurface>& surfaces, Tree& tree);

}  // namespace q3::bspstage
