#include "model_surfaces.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "face_surfaces.h"
#include "log.h"
#include "model.h"
#include "model_clip.h"
#include "model_transform.h"
#include "script.h"
#include "shader_info.h"
#include "vfs.h"

namespace q3::bspstage {
namespace {

constexpr int kRandomMapGenerator = 1;  // SoF2's RMG_BSP spawnflag: the -rename suffix
constexpr int kForceMeta = 4;
constexpr int kColorToAlpha = 32;  // the vertex colour's grey goes to alpha, colour becomes white

const std::string* keyOf(const map::MapEntity& e, std::initializer_list<const char*> keys) {
    for (const char* k : keys)
        if (const std::string* v = e.find(k)) return v;
    return nullptr;
}

std::string label(const map::MapEntity& e) { return "Entity " + std::to_string(e.number) + " (misc_model)"; }

struct Remap {
    std::string from, to;
};

std::vector<Remap> remapsOf(const map::MapEntity& e, Log& log) {
    std::vector<Remap> out;
    for (const auto& [key, value] : e.pairs) {
        if (key.size() < 6 || !equalsNoCase(std::string_view(key).substr(0, 6), "_remap")) continue;
        const size_t split = value.find(';');
        if (split == std::string::npos || split == 0 || split + 1 == value.size()) {
            log.warning(label(e) + ": _remap needs \"from;to\", got '" + value + "'");
            continue;
        }
        out.push_back({value.substr(0, split), value.substr(split + 1)});
    }
    return out;
}

// The longest `from` that ends the name wins; "*" applies when nothing else does.
std::string remapped(const std::string& shader, const std::vector<Remap>& remaps) {
    const std::string* to = nullptr;
    size_t longest = 0;
    for (const Remap& r : remaps) {
        if (r.from == "*" && longest == 0) {
            to = &r.to;
        } else if (r.from.size() <= shader.size() && r.from.size() > longest &&
                   equalsNoCase(std::string_view(shader).substr(shader.size() - r.from.size()), r.from)) {
            to = &r.to;
            longest = r.from.size();
        }
    }
    return to ? *to : shader;
}

Vec3 vectorKey(const map::MapEntity& e, const char* key, Vec3 fallback) {
    const std::string* v = e.find(key);
    if (!v) return fallback;
    float x = 0, y = 0, z = 0;
    const int read = std::sscanf(v->c_str(), "%f %f %f", &x, &y, &z);
    if (read == 1) return {x, x, x};
    return read == 3 ? Vec3{x, y, z} : fallback;
}

// Keys read as floats and the parent's origin taken off in floats, as q3map2 does.
ModelTransform transformOf(const map::MapEntity& e, const DVec3& parentOrigin) {
    const Vec3 origin = vectorKey(e, "origin", {0, 0, 0}) -
                        Vec3{float(parentOrigin.x), float(parentOrigin.y), float(parentOrigin.z)};
    Vec3 scale{1, 1, 1};
    if (e.find("modelscale_vec")) {
        scale = vectorKey(e, "modelscale_vec", scale);
    } else if (const std::string* s = e.find("modelscale")) {
        scale = Vec3::splat(float(std::atof(s->c_str())));
    }
    float pitch = 0, yaw = 0, roll = 0;
    if (const std::string* a = e.find("angles")) {
        std::sscanf(a->c_str(), "%f %f %f", &pitch, &yaw, &roll);
    } else if (const std::string* a = e.find("angle")) {
        yaw = float(std::atof(a->c_str()));
    }
    return ModelTransform::place(origin, pitch, yaw, roll, scale);
}

// Models loaded once per name and frame, failures too (each entity using one is warned about).
class ModelCache {
public:
    const std::vector<model::Surface>* get(const std::string& name, int frame, const ModelInputs& inputs,
                                          const std::string& who, Log& log) {
        auto [it, added] = models_.try_emplace({toLower(name), frame});
        if (added) {
            try {
                if (!inputs.vfs) throw model::ModelError(name + ": no game folders to read models from");
                const model::FileReader read = [&](const std::string& path) { return inputs.vfs->read(path); };
                it->second.surfaces = model::loadModel(name, read, {frame, inputs.maxSurfaceVerts});
            } catch (const model::ModelError& err) {
                it->second.error = err.what();
            }
        }
        if (!it->second.error.empty()) {
            log.warning(who + ": model skipped: " + it->second.error);
            return nullptr;
        }
        return &it->second.surfaces;
    }

private:
    struct Entry {
        std::vector<model::Surface> surfaces;
        std::string error;
    };
    std::map<std::pair<std::string, int>, Entry> models_;
};

// The remaps of the entity's _skin/skin key; nullopt when there is none or its file is missing
// (q3map2 then draws every surface under its own shader).
std::optional<std::vector<model::SkinRemap>> skinOf(const map::MapEntity& e, const std::string& modelName,
                                                     const Vfs* vfs, Log& log) {
    const std::string* skin = keyOf(e, {"_skin", "skin"});
    if (!skin || skin->empty() || !vfs) return std::nullopt;
    const std::string file = model::skinFileName(modelName, *skin);
    const std::optional<std::vector<uint8_t>> bytes = vfs->read(file);
    if (!bytes) {
        log.debug(label(e) + ": skin file " + file + " not found");
        return std::nullopt;
    }
    std::vector<model::SkinRemap> remaps = model::parseSkin(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
    if (remaps.empty()) return std::nullopt;
    log.info("Using skin " + *skin + " of " + modelName);
    return remaps;
}

// q3map2 normalises model normals in doubles: the last bits differ from a float normalisation.
Vec3 normalizedInDoubles(const Vec3& v) {
    const double x = v.x, y = v.y, z = v.z, len = std::sqrt(x * x + y * y + z * z);
    if (len == 0) return {0, 0, 0};
    return {float(x / len), float(y / len), float(z / len)};
}

// Model colours to bytes as q3map2 does (scaled, clamped, truncated).
uint8_t colorByte(float c) { return uint8_t(std::clamp(c * 255.0f, 0.0f, 255.0f)); }

void setColor(bsp::DrawVert& dv, const float (&color)[4], bool colorToAlpha) {
    if (colorToAlpha) {
        const float grey = color[0] * 0.2989f + color[1] * 0.5870f + color[2] * 0.1140f;
        dv.color[0] = dv.color[1] = dv.color[2] = 255;
        dv.color[3] = colorByte(grey);
    } else {
        for (int i = 0; i < 4; ++i) dv.color[i] = colorByte(color[i]);
    }
}

// A model surface as a triangle surface under `shader`, its vertices moved by `transform`.
DrawSurface triangleSurface(const model::Surface& surface, const ShaderInfo& shader, const std::string& shaderName,
                            const ModelTransform& transform, bool colorToAlpha, LoadedMap& map) {
    // q3map2 names a shader without a script as the model spells it, less the extension.
    if (!shader.explicitScript)
        map.implicitShaderNames.try_emplace(&shader, shaderName.substr(0, shaderKey(shaderName).size()));
    DrawSurface ds;
    ds.kind = SurfaceKind::Triangles;
    ds.shader = &shader;
    for (const model::Vertex& v : surface.verts) {
        bsp::DrawVert dv{};
        transform.point(v.xyz).toArray(dv.xyz);
        normalizedInDoubles(transform.normal(v.normal)).toArray(dv.normal);
        if (shader.tcGen) {
            const Vec3 p = xyzOf(dv);
            dv.st[0] = dot(shader.tcGenVectors[0], p);
            dv.st[1] = dot(shader.tcGenVectors[1], p);
        } else {
            dv.st[0] = v.st[0];
            dv.st[1] = v.st[1];
        }
        setColor(dv, v.color, colorToAlpha);
        ds.verts.push_back(dv);
    }
    ds.indexes = surface.indexes;
    if (transform.leftHanded())
        for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) std::swap(ds.indexes[i + 1], ds.indexes[i + 2]);
    return ds;
}

}  // namespace

std::vector<DrawSurface> scaledModelSurfaces(const std::string& modelName, float scale, const ModelInputs& inputs,
                                             LoadedMap& map, const std::string& who, Log& log) {
    ModelCache cache;
    std::vector<DrawSurface> out;
    const std::vector<model::Surface>* surfaces = cache.get(modelName, 0, inputs, who, log);
    if (!surfaces) return out;
    const ModelTransform transform = ModelTransform::place({0, 0, 0}, 0, 0, 0, Vec3::splat(scale));
    for (const model::Surface& surface : *surfaces) {
        const ShaderInfo& shader = inputs.shaders.find(surface.shader);
        out.push_back(triangleSurface(surface, shader, surface.shader, transform, false, map));
    }
    return out;
}

void addModelSurfaces(const BspEntity& parent, bool isWorld, LoadedMap& map, const ModelInputs& inputs,
                      std::vector<DrawSurface>& out, std::vector<Brush>& clipBrushes, Log& log) {
    const std::string targetName =
        isWorld ? std::string() : parent.source->value("_targetname", parent.source->value("targetname"));
    if (!isWorld && targetName.empty()) return;
    ModelCache cache;
    for (const map::MapEntity& e : inputs.file.entities) {
        if (e.number == 0 || !equalsNoCase(e.classname(), "misc_model")) continue;
        const std::string* target = keyOf(e, {"_target", "target"});
        if ((target ? *target : std::string()) != targetName) continue;
        const std::string* modelName = e.find("model");
        if (!modelName) {
            log.warning("entity#" + std::to_string(e.number) + " misc_model without a model key");
            continue;
        }
        const int spawnFlags = std::atoi(e.value("spawnflags").c_str());
        float clipDepth = inputs.clip.clipDepth;
        if (const std::string* d = e.find("_clipdepth")) clipDepth = float(std::atof(d->c_str()));
        bool refusedClip = false;
        // Surfaces autoclip may use: their index in `out` and their vertices placed in doubles.
        std::vector<std::pair<size_t, std::vector<DVec3>>> clipped;
        const int frame = std::atoi(e.value("_frame", e.value("frame")).c_str());
        const std::vector<model::Surface>* surfaces = cache.get(*modelName, frame, inputs, label(e), log);
        if (!surfaces) continue;
        const std::optional<std::vector<model::SkinRemap>> skin = skinOf(e, *modelName, inputs.vfs, log);
        const ModelTransform transform = transformOf(e, parent.origin);
        const std::vector<Remap> remaps = remapsOf(e, log);
        // Lightmap sample size and scale, shading angle, ambient light and cel shader come from the
        // misc_model's own keys (not its parent's), the shadow flags from its or else its parent's.
        const EntitySurfaceParams keys = entitySurfaceParams(e, isWorld);
        const int cast = std::atoi(e.value("_castShadows", e.value("_cs", parent.source->value("_castShadows",
                                   parent.source->value("_cs", isWorld ? "1" : "0")))).c_str());
        const int receive = std::atoi(e.value("_receiveShadows", e.value("_rs", parent.source->value("_receiveShadows",
                                      parent.source->value("_rs", "1")))).c_str());
        for (const model::Surface& surface : *surfaces) {
            std::string shaderName = surface.shader;
            if (skin) {  // a skin names every surface drawn; the others are left out
                const auto to = std::find_if(skin->begin(), skin->end(), [&](const model::SkinRemap& r) {
                    return equalsNoCase(r.from, surface.shader);
                });
                if (to == skin->end()) continue;
                shaderName = to->to;
            }
            shaderName = remapped(shaderName, remaps);
            if (inputs.renameShaders)
                shaderName = shaderName.substr(0, shaderKey(shaderName).size()) +
                             ((spawnFlags & kRandomMapGenerator) ? "_RMG_BSP" : "_BSP");
            const ShaderInfo& shader = inputs.shaders.find(shaderName);
            DrawSurface ds = triangleSurface(surface, shader, shaderName, transform, spawnFlags & kColorToAlpha, map);
            // Forced meta triangles join the meta pipeline: always for a q3map_forceMeta shader,
            // otherwise only with -meta (without it they stay a triangle soup).
            if (shader.forceMeta || (spawnFlags & kForceMeta)) ds.kind = SurfaceKind::ForcedMeta;
            ds.mapEntityNum = parent.mapEntityNum;
            ds.castShadows = cast;
            ds.receiveShadows = receive;
            ds.sampleSize = keys.sampleSize;
            ds.lightmapScale = keys.lightmapScale;
            ds.shadeAngle = keys.shadeAngle;
            ds.modelEntity = e.number;
            const ClipMode mode = clipModeFor(spawnFlags, shader);
            if (mode != ClipMode::None && mode != ClipMode::Unknown) {
                std::vector<DVec3> positions;
                for (const model::Vertex& v : surface.verts) positions.push_back(transform.pointInDoubles(v.xyz));
                clipped.emplace_back(out.size(), std::move(positions));
            }
            if (mode == ClipMode::Unknown && !refusedClip) {
                log.warning(label(e) + ": autoclip spawnflags " + std::to_string(spawnFlags & clipflag::All) +
                            " name no clipping mode; the model gets no clip brushes");
                refusedClip = true;
            }
            out.push_back(std::move(ds));
        }
        if (clipped.empty()) continue;
        ClipRequest request;
        request.spawnFlags = spawnFlags;
        request.mapEntityNum = parent.mapEntityNum;
        request.clipDepth = clipDepth;
        request.modelName = modelName;
        if (inputs.clip.debugClip) {
            request.debugShaders[0] = &inputs.shaders.find("debugclip2");
            request.debugShaders[1] = &inputs.shaders.find("debugclip");
        }
        std::vector<ClipSurface> clipSurfaces;
        for (auto& [index, positions] : clipped) clipSurfaces.push_back({&out[index], std::move(positions)});
        ClipBrushes clip = clipBrushesForModel(clipSurfaces, request, inputs.clip, map.planes);
        for (const std::string& w : clip.warnings) log.warning(w);
        for (Brush& b : clip.brushes) clipBrushes.push_back(std::move(b));
    }
}

}  // namespace q3::bspstage
