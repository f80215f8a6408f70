// Models through Assimp, set up as q3map2 2.5.17n sets up its importer (model.cpp LoadModel,
// assimp_init), so that the same library gives the same meshes, vertex order and shader names.
#include <assimp/Importer.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstring>
#include <map>

#include "model.h"

namespace q3::model {
namespace {

// Assimp's files come from the caller's reader; a model's companions (an .obj's .mtl) too.
class ReaderIO : public Assimp::IOSystem {
public:
    explicit ReaderIO(const FileReader& read) : read_(read) {}

    bool Exists(const char* path) const override { return load(path) != nullptr; }
    char getOsSeparator() const override { return '/'; }

    Assimp::IOStream* Open(const char* path, const char* mode) override {
        if (mode && std::strchr(mode, 'w')) return nullptr;  // never written
        const std::vector<uint8_t>* bytes = load(path);
        if (!bytes) return nullptr;
        auto* copy = new uint8_t[bytes->size() + 1];  // the stream owns it; +1: never a null buffer
        if (!bytes->empty()) std::memcpy(copy, bytes->data(), bytes->size());  // an empty file has no data()
        return new Assimp::MemoryIOStream(copy, bytes->size(), true);
    }
    void Close(Assimp::IOStream* stream) override { delete stream; }

private:
    static std::string normalised(std::string path) {
        for (char& c : path)
            if (c == '\\') c = '/';
        for (size_t at; (at = path.find("/./")) != std::string::npos;) path.erase(at, 2);
        while (path.rfind("./", 0) == 0) path.erase(0, 2);
        return path;
    }
    // Each file is read once per import: Assimp asks whether it exists before opening it.
    const std::vector<uint8_t>* load(const char* rawPath) const {
        const std::string path = normalised(rawPath ? rawPath : "");
        auto it = files_.find(path);
        if (it == files_.end()) it = files_.emplace(path, read_(path)).first;
        return it->second ? &*it->second : nullptr;
    }

    const FileReader& read_;
    mutable std::map<std::string, std::optional<std::vector<uint8_t>>> files_;
};

void configure(Assimp::Importer& importer, const LoadOptions& options) {
    importer.SetPropertyBool(AI_CONFIG_PP_PTV_ADD_ROOT_TRANSFORMATION, true);
    // Assimp's Y up becomes Quake's Z up: a quarter turn about X.
    importer.SetPropertyMatrix(AI_CONFIG_PP_PTV_ROOT_TRANSFORMATION,
                               aiMatrix4x4(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1));
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    importer.SetPropertyString(AI_CONFIG_IMPORT_MDL_COLORMAP, "gfx/palette.lmp");
    importer.SetPropertyBool(AI_CONFIG_IMPORT_MD3_LOAD_SHADERS, false);
    importer.SetPropertyString(AI_CONFIG_IMPORT_MD3_SHADER_SRC, "scripts/");
    importer.SetPropertyBool(AI_CONFIG_IMPORT_MD3_HANDLE_MULTIPART, false);
    // Tangents vary per corner and would keep identical vertices from being joined.
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_TANGENTS_AND_BITANGENTS);
    importer.SetPropertyInteger(AI_CONFIG_PP_SLM_VERTEX_LIMIT, options.maxSurfaceVerts);
    importer.SetPropertyInteger(AI_CONFIG_IMPORT_GLOBAL_KEYFRAME, options.frame);
}

constexpr unsigned kImportSteps = aiProcess_GenNormals | aiProcess_JoinIdenticalVertices | aiProcess_Triangulate |
                                  aiProcess_GenUVCoords | aiProcess_SortByPType | aiProcess_FindDegenerates |
                                  aiProcess_FindInvalidData | aiProcess_ValidateDataStructure | aiProcess_FlipUVs |
                                  aiProcess_FlipWindingOrder | aiProcess_PreTransformVertices |
                                  aiProcess_RemoveComponent | aiProcess_SplitLargeMeshes;

Surface surfaceOf(const aiScene& scene, const aiMesh& mesh, const std::string& path) {
    Surface s;
    s.name = mesh.mName.C_Str();
    const aiMaterial* material = mesh.mMaterialIndex < scene.mNumMaterials ? scene.mMaterials[mesh.mMaterialIndex] : nullptr;
    std::string materialName, texture;
    if (material) {
        materialName = material->GetName().C_Str();
        aiString name;
        if (material->Get(AI_MATKEY_TEXTURE_DIFFUSE(0), name) == aiReturn_SUCCESS) texture = name.C_Str();
    }
    s.shader = importedShaderName(materialName, texture, path);
    s.verts.resize(mesh.mNumVertices);
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
        Vertex& v = s.verts[i];
        v.xyz = {mesh.mVertices[i].x, mesh.mVertices[i].y, mesh.mVertices[i].z};
        if (mesh.HasNormals()) v.normal = {mesh.mNormals[i].x, mesh.mNormals[i].y, mesh.mNormals[i].z};
        if (mesh.HasTextureCoords(0)) {
            v.st[0] = mesh.mTextureCoords[0][i].x;
            v.st[1] = mesh.mTextureCoords[0][i].y;
        }
        if (mesh.HasVertexColors(0)) {
            const aiColor4D& c = mesh.mColors[0][i];
            v.color[0] = c.r, v.color[1] = c.g, v.color[2] = c.b, v.color[3] = c.a;
        }
    }
    s.indexes.reserve(size_t(mesh.mNumFaces) * 3);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines were removed; nothing else is left
        for (unsigned c = 0; c < 3; ++c) s.indexes.push_back(int(face.mIndices[c]));
    }
    return s;
}

// Meshes in node order, depth first, triangle meshes only.
void collect(const aiScene& scene, const aiNode& node, const std::string& path, std::vector<Surface>& out) {
    for (unsigned n = 0; n < node.mNumMeshes; ++n) {
        if (node.mMeshes[n] >= scene.mNumMeshes) continue;
        const aiMesh& mesh = *scene.mMeshes[node.mMeshes[n]];
        if (mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) out.push_back(surfaceOf(scene, mesh, path));
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], path, out);
}

}  // namespace

bool importerReads(const std::string& extension) {
    const Assimp::Importer importer;
    return importer.IsExtensionSupported(extension.c_str());
}

std::vector<Surface> loadModel(const std::string& path, const FileReader& read, const LoadOptions& options) {
    Assimp::Importer importer;
    importer.SetIOHandler(new ReaderIO(read));  // the importer owns it
    configure(importer, options);
    const aiScene* scene = importer.ReadFile(path.c_str(), kImportSteps);
    if (!scene) {
        std::string why = importer.GetErrorString();
        while (!why.empty() && (why.back() == '\n' || why.back() == '\r' || why.back() == ' ')) why.pop_back();
        for (char& c : why)
            if (c == '\n' || c == '\r') c = ' ';
        throw ModelError(path + ": " + (why.empty() ? std::string("cannot be imported") : why));
    }
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) throw ModelError(path + ": the importer read it incompletely");
    std::vector<Surface> out;
    if (scene->mRootNode) collect(*scene, *scene->mRootNode, path, out);
    return out;
}

}  // namespace q3::model
