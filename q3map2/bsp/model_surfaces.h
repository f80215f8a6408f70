// misc_model entities baked into a model's surfaces (q3map2 model.cpp AddTriangleModels,
// InsertModel): every misc_model whose target names the entity (none for the world) has its model
// loaded through the VFS, moved by its origin (less the parent's), angles and scale, its shaders
// remapped by a _skin file and _remap keys, and each model surface becomes a triangle surface, or a
// forced meta one (spawnflag 4 or a q3map_forceMeta shader) for the meta pipeline. Every format of
// libs/model is read; the autoclip spawnflags (or a q3map_clipModel shader) make clip brushes
// (model_clip.h). A missing or broken model file is skipped with a warning naming the entity.
#pragma once

#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"
#include "model_clip.h"

namespace q3 {
class Log;
class ShaderTable;
class Vfs;
}  // namespace q3

namespace q3::bspstage {

struct ModelInputs {
    const map::MapFile& file;
    const ShaderTable& shaders;
    const Vfs* vfs;  // nullptr: no model can be loaded (each one is warned about)
    // -rename (SoF2): shader names get _BSP, or _RMG_BSP with spawnflag 1, in place of an extension.
    bool renameShaders = false;
    int maxSurfaceVerts = 999;  // imported meshes are split above this many vertices (-mv may raise it)
    ClipOptions clip;
};

// Appends the triangle surfaces of the misc_models attached to `parent` (a LoadedMap entity), and
// their clip brushes in the order made (see prependClipBrushes). Shaders without a script are
// recorded in `map` under the spelling the model gives them.
void addModelSurfaces(const BspEntity& parent, bool isWorld, LoadedMap& map, const ModelInputs& inputs,
                      std::vector<DrawSurface>& out, std::vector<Brush>& clipBrushes, Log& log);

// The surfaces of one model file, scaled about its origin, under the shaders its surfaces name
// (q3map2 InsertModel without remaps, skin or clip brushes): what q3map_foliage places. Empty, with
// a warning naming `who`, when the model cannot be loaded.
std::vector<DrawSurface> scaledModelSurfaces(const std::string& modelName, float scale, const ModelInputs& inputs,
                                             LoadedMap& map, const std::string& who, Log& log);

}  // namespace q3::bspstage
