#include "model_surfaces.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>

#include "log.h"
#include "md3_model.h"
#include "script.h"
#include "shader_info.h"
#include "vfs.h"

namespace q3::bspstage {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kRandomMapGenerator = 1;  // SoF2's RMG_BSP spawnflag: the -rename suffix
constexpr int kClipFlags = 2 | 8 | 16 | 128 | 256 | 512 | 1024 | 2048 | 4096;  // autoclip spawnflags
constexpr int kForceMeta = 4;
constexpr int kColorToAlpha = 32;

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

DVec3 vectorKey(const map::MapEntity& e, const char* key, DVec3 fallback) {
    const std::string* v = e.find(key);
    if (!v) return fallback;
    double x = 0, y = 0, z = 0;
    const int read = std::sscanf(v->c_str(), "%lf %lf %lf", &x, &y, &z);
    if (read == 1) return {x, x, x};
    return read == 3 ? DVec3{x, y, z} : fallback;
}

ModelTransform transformOf(const map::MapEntity& e, const DVec3& parentOrigin) {
    const DVec3 origin = parseVectorKey(e.value("origin")) - parentOrigin;
    DVec3 scale{1, 1, 1};
    if (e.find("modelscale_vec")) {
        scale = vectorKey(e, "modelscale_vec", scale);
    } else if (const std::string* s = e.find("modelscale")) {
        scale = DVec3::splat(std::atof(s->c_str()));
    }
    double pitch = 0, yaw = 0, roll = 0;
    if (const std::string* a = e.find("angles")) {
        std::sscanf(a->c_str(), "%lf %lf %lf", &pitch, &yaw, &roll);
    } else if (const std::string* a = e.find("angle")) {
        yaw = std::atof(a->c_str());
    }
    return modelTransform(origin, pitch, yaw, roll, scale);
}

}  // namespace

Vec3 ModelTransform::point(const Vec3& p) const {
    Vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = float(m[i][0] * p.x + m[i][1] * p.y + m[i][2] * p.z + m[i][3]);
    return out;
}

Vec3 ModelTransform::direction(const Vec3& d) const {
    // Inverse transpose of the 3x3 part: the cofactor matrix over the determinant.
    auto c = [&](int r, int k) { return m[(r + 1) % 3][(k + 1) % 3] * m[(r + 2) % 3][(k + 2) % 3] -
                                        m[(r + 1) % 3][(k + 2) % 3] * m[(r + 2) % 3][(k + 1) % 3]; };
    const double det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    Vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = float((c(i, 0) * d.x + c(i, 1) * d.y + c(i, 2) * d.z) / det);
    return out;
}

bool ModelTransform::leftHanded() const {
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return det < 0;
}

ModelTransform modelTransform(const DVec3& origin, double pitch, double yaw, double roll, const DVec3& scale) {
    const double x = roll * kPi / 180, y = pitch * kPi / 180, z = yaw * kPi / 180;
    const double cx = std::cos(x), sx = std::sin(x), cy = std::cos(y), sy = std::sin(y), cz = std::cos(z), sz = std::sin(z);
    // Rz * Ry * Rx, columns scaled.
    const double r[3][3] = {{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
                            {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
                            {-sy, cy * sx, cy * cx}};
    ModelTransform t;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) t.m[i][j] = r[i][j] * scale[j];
        t.m[i][3] = origin[i];
    }
    return t;
}

void addModelSurfaces(const BspEntity& parent, bool isWorld, LoadedMap& map, const ModelInputs& inputs,
                      std::vector<DrawSurface>& out, Log& log) {
    const std::string targetName =
        isWorld ? std::string() : parent.source->value("_targetname", parent.source->value("targetname"));
    if (!isWorld && targetName.empty()) return;
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
        if (spawnFlags & (kClipFlags | kForceMeta | kColorToAlpha)) {
            log.warning(label(e) + ": spawnflags " + std::to_string(spawnFlags) +
                        " (autoclip, forced meta or colour to alpha) are not supported by this build; model skipped");
            continue;
        }
        if (e.find("_skin") || e.find("skin")) {
            log.warning(label(e) + ": model skins are not supported by this build; model skipped");
            continue;
        }
        const std::string extension = toLower(std::filesystem::path(*modelName).extension().string());
        if (extension != ".md3") {
            log.warning(label(e) + ": " + *modelName + ": only MD3 models are read by this build; model skipped");
            continue;
        }
        std::optional<std::vector<uint8_t>> bytes = inputs.vfs ? inputs.vfs->read(*modelName) : std::nullopt;
        if (!bytes) {
            log.warning(label(e) + ": model " + *modelName + " not found");
            continue;
        }
        std::vector<ModelSurface> surfaces;
        try {
            surfaces = parseMd3(*bytes, std::atoi(e.value("_frame", e.value("frame")).c_str()), *modelName);
        } catch (const std::exception& err) {
            log.warning(label(e) + ": " + err.what());
            continue;
        }
        const ModelTransform transform = transformOf(e, parent.origin);
        const std::vector<Remap> remaps = remapsOf(e, log);
        const int cast = std::atoi(e.value("_castShadows", e.value("_cs", parent.source->value("_castShadows",
                                   parent.source->value("_cs", isWorld ? "1" : "0")))).c_str());
        const int receive = std::atoi(e.value("_receiveShadows", e.value("_rs", parent.source->value("_receiveShadows",
                                      parent.source->value("_rs", "1")))).c_str());
        for (const ModelSurface& surface : surfaces) {
            std::string shaderName = remapped(surface.shader, remaps);
            if (inputs.renameShaders)
                shaderName = shaderName.substr(0, shaderKey(shaderName).size()) +
                             ((spawnFlags & kRandomMapGenerator) ? "_RMG_BSP" : "_BSP");
            const ShaderInfo& shader = inputs.shaders.find(shaderName);
            if (shader.forceMeta) {
                log.warning(label(e) + ": shader " + shader.name +
                            " forces meta surfaces, which this build does not make; model surface skipped");
                continue;
            }
            // q3map2 names a shader without a script as the model spells it, less the extension.
            if (!shader.explicitScript)
                map.implicitShaderNames.try_emplace(&shader, shaderName.substr(0, shaderKey(shaderName).size()));
            DrawSurface ds;
            ds.kind = SurfaceKind::Triangles;
            ds.shader = &shader;
            ds.mapEntityNum = parent.mapEntityNum;
            ds.castShadows = cast;
            ds.receiveShadows = receive;
            for (const ModelVertex& v : surface.verts) {
                bsp::DrawVert dv{};
                transform.point(v.xyz).toArray(dv.xyz);
                Vec3 n = transform.direction(v.normal);
                normalizeInPlace(n);
                n.toArray(dv.normal);
                if (shader.tcGen) {
                    const Vec3 p = xyzOf(dv);
                    dv.st[0] = dot(shader.tcGenVectors[0], p);
                    dv.st[1] = dot(shader.tcGenVectors[1], p);
                } else {
                    dv.st[0] = v.st[0];
                    dv.st[1] = v.st[1];
                }
                for (uint8_t& c : dv.color) c = 255;
                ds.verts.push_back(dv);
            }
            ds.indexes = surface.indexes;
            if (transform.leftHanded())
                for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) std::swap(ds.indexes[i + 1], ds.indexes[i + 2]);
            out.push_back(std::move(ds));
        }
    }
}

}  // namespace q3::bspstage
