// Fog volumes (q3map2 fog.cpp, writebsp.cpp EmitFogs): brushes whose content shader has fogParms,
// in entity and brush order, and the worldspawn _fog / fog global fog last. World faces crossing a
// fog brush are cut by its planes (the inside piece is fogged, the outside pieces become surfaces of
// their own), patches by its bottom and top planes; brush model surfaces take the fog their bounds
// overlap most.
#pragma once

#include <vector>

#include "bsp_builder.h"
#include "draw_surface.h"
#include "face_surfaces.h"

namespace q3 {
class Log;
class ShaderTable;
}  // namespace q3

namespace q3::bspstage {

struct MapFog {
    const ShaderInfo* shader = nullptr;
    int entity = -1;       // entity (index in LoadedMap) and brush of the volume; -1 for the global fog
    int brush = -1;
    int visibleSide = -1;  // forced by q3map_fogDir, else chosen when written
};

struct MapFogs {
    std::vector<MapFog> fogs;
    int defaultFog = kNoFog;  // the global fog, which every surface not in a volume takes
};

// Throws CompileError when the global fog names a shader that does not exist.
MapFogs createMapFogs(const LoadedMap& map, const ShaderTable& shaders, Log& log);

struct FogCounts {
    int faceFragments = 0;
    int patchFragments = 0;
    int fogged = 0;
};

// Fogs the world's surfaces (all of `surfaces`), cutting faces and patches; new pieces are appended.
FogCounts fogWorldSurfaces(std::vector<DrawSurface>& surfaces, const MapFogs& fogs, const LoadedMap& map,
                           const FaceContext& context, const std::vector<EntitySurfaceParams>& paramsByMapEntity);

// The fog whose volume (grown by `epsilon`) overlaps `bounds` most, else the default fog.
int fogForBounds(const DBounds& bounds, const MapFogs& fogs, const LoadedMap& map, double epsilon);

// The fog lump; `brushOutputs[e]` is the first BSP brush of entity e (-1 when it has none).
void emitFogs(const MapFogs& fogs, const LoadedMap& map, const std::vector<int>& brushOutputs, BspBuilder& builder,
              Log& log);

}  // namespace q3::bspstage
