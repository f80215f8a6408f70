// misc_model entities baked into a model's surfaces (q3map2 model.cpp AddTriangleModels,
// InsertModel): every misc_model whose target names the entity (none for the world) has its model
// loaded through the VFS, moved by its origin (less the parent's), angles and scale, its shaders
// remapped by _remap keys, and each model surface becomes a triangle surface. MD3 models are read;
// other formats and autoclip are refused with a warning naming the entity.
#pragma once

#include <vector>

#include "bsp_brushes.h"
#include "draw_surface.h"

namespace q3 {
class Log;
class ShaderTable;
class Vfs;
}  // namespace q3

namespace q3::bspstage {

struct ModelTransform {
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};  // rotation * scale, then translation

    Vec3 point(const Vec3& p) const;
    Vec3 direction(const Vec3& d) const;  // by the inverse transpose, for normals (not normalised)
    bool leftHanded() const;
};

// Origin, then yaw (Z), pitch (Y) and roll (X) in degrees, then scale (q3map2's euler xyz order).
ModelTransform modelTransform(const DVec3& origin, double pitch, double yaw, double roll, const DVec3& scale);

struct ModelInputs {
    const map::MapFile& file;
    const ShaderTable& shaders;
    const Vfs* vfs;  // nullptr: no model can be loaded (each one is warned about)
    // -rename (SoF2): shader names get _BSP, or _RMG_BSP with spawnflag 1, in place of an extension.
    bool renameShaders = false;
};

// Appends the triangle surfaces of the misc_models attached to `parent` (a LoadedMap entity).
// Shaders without a script are recorded in `map` under the spelling the model gives them.
void addModelSurfaces(const BspEntity& parent, bool isWorld, LoadedMap& map, const ModelInputs& inputs,
                      std::vector<DrawSurface>& out, Log& log);

}  // namespace q3::bspstage
