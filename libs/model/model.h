// Models for misc_model, independent of their file format: each surface is a triangle list with one
// shader name. Every format goes through Assimp (md3, obj, ase, lwo, 3ds, fbx, dae, ply, ...) with
// the import settings q3map2 2.5.17n uses, so surface order, vertex order, generated normals and
// shader names follow it, MD3 included (Assimp 5.2 reads an MD3's first frame only, and its
// surfaces last first). Files come through a caller-given reader (the VFS), including those a
// model names (an .obj's .mtl, an MD3's <name>_default.skin).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "vec3.h"

namespace q3::model {

struct Vertex {
    Vec3 xyz;
    Vec3 normal;
    float st[2] = {0, 0};
    float color[4] = {1, 1, 1, 1};  // vertex colour channel 0, 0..1 (white when the file has none)
};

struct Surface {
    std::string name;
    std::string shader;  // as the model names it (an extension may remain)
    std::vector<Vertex> verts;
    std::vector<int> indexes;  // triangles
};

// A model that cannot be used: missing, unreadable, broken or of an unknown format. The message is
// one line naming the file.
class ModelError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Reads a file by its game path ("models/x/y.obj"); nullopt when there is none.
using FileReader = std::function<std::optional<std::vector<uint8_t>>(const std::string& path)>;

struct LoadOptions {
    int frame = 0;               // animation frame, for the readers that take one
    int maxSurfaceVerts = 999;   // larger meshes are split (q3map2's maxSurfaceVerts)
};

// The model at `path`, the reader chosen by Assimp, with q3map2's post-processing (Y-up turned Z-up,
// normals generated, identical vertices joined, triangulated, UVs flipped, winding flipped,
// hierarchy baked, large meshes split). Throws ModelError.
std::vector<Surface> loadModel(const std::string& path, const FileReader& read, const LoadOptions& options);
bool importerReads(const std::string& extension);  // ".obj": whether Assimp has a reader for it

// q3map2's shader name for an imported material: its diffuse texture (less extension) unless the
// material is named like a game shader ("textures/...", "models/..."), else the material name;
// a bare name is taken from the model's folder, an absolute or ".." path is cut at "/models/" or
// "/textures/" (else the model's folder and its file name).
std::string importedShaderName(const std::string& materialName, const std::string& diffuseTexture,
                               const std::string& modelPath);

// The path less the extension of its file name ("a.b/c.tga" -> "a.b/c").
std::string extensionless(std::string_view path);

// A .skin file: "replace FROM TO" and "FROM,TO" lines, in order; other lines are skipped.
struct SkinRemap {
    std::string from, to;
};
std::vector<SkinRemap> parseSkin(std::string_view text);
// The .skin file q3map2 reads for skin `skin` of `modelPath`: "<model>_<N>.skin" for a number
// (DarkPlaces), else "<model less extension>_<skin>.skin" (Quake 3).
std::string skinFileName(const std::string& modelPath, const std::string& skin);

}  // namespace q3::model
