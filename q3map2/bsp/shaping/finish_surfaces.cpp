#include "finish_surfaces.h"

#include <algorithm>
#include <array>
#include <map>

#include "log.h"
#include "map_file.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

// The cel shader of one .map entity: its own _celshader, else worldspawn's, else the global one.
const ShaderInfo* celShaderOf(int mapEntityNum, const FinishInputs& in) {
    const std::string* value = nullptr;
    for (const map::MapEntity& e : in.file.entities)
        if (e.number == mapEntityNum) value = e.find("_celshader");
    if (!value && !in.file.entities.empty()) value = in.file.entities.front().find("_celshader");
    if (value) return &in.shaders.find("textures/" + *value);
    return in.globalCelShader.empty() ? nullptr : &in.shaders.find(in.globalCelShader);
}

DrawSurface copyWith(const DrawSurface& src, const ShaderInfo& shader) {
    DrawSurface ds = src;
    ds.shader = &shader;
    ds.brush = ds.side = -1;  // a copy stands for no brush side
    ds.fogBackFace = false;
    ds.metaSides.clear();
    return ds;
}

}  // namespace

int finishSurfaces(std::vector<DrawSurface>& surfaces, const FinishInputs& in) {
    const size_t before = surfaces.size();
    std::map<int, const ShaderInfo*> celByEntity;  // a model's surfaces mostly share one entity
    for (size_t i = 0; i < before; ++i) {
        const int entity = surfaces[i].modelEntity >= 0 ? surfaces[i].modelEntity : surfaces[i].mapEntityNum;
        auto [it, added] = celByEntity.try_emplace(entity, nullptr);
        if (added) it->second = celShaderOf(entity, in);
        surfaces[i].celShader = it->second;
    }
    // Copies are appended while walking and finished in their turn (they keep the cel shader).
    for (size_t i = 0; i < surfaces.size(); ++i) {
        if (int(surfaces.size()) > in.maxSurfaces)
            throw CompileError("max_map_draw_surfs (" + std::to_string(in.maxSurfaces) + ") exceeded by copies of shader '" +
                               surfaces[i].shader->name + "' (q3map_cloneShader / q3map_backShader)");
        const ShaderInfo& si = *surfaces[i].shader;
        if (const ShaderInfo* cel = surfaces[i].celShader; cel && !si.isTranslucent() && !si.isSky()) {
            DrawSurface ds = copyWith(surfaces[i], *cel);
            ds.planar = false;
            ds.planeNum = -1;
            ds.celShader = nullptr;  // cel surfaces are not cel shaded again
            surfaces.push_back(std::move(ds));
        }
        if (surfaces[i].backSide) continue;
        if (!si.cloneShader.empty()) surfaces.push_back(copyWith(surfaces[i], in.shaders.find(si.cloneShader)));
        if (!si.backShader.empty()) {
            DrawSurface ds = copyWith(surfaces[i], in.shaders.find(si.backShader));
            ds.backSide = true;
            surfaces.push_back(std::move(ds));
        }
    }
    return int(surfaces.size() - before);
}

void applyColorMods(std::span<const ShaderColorMod> mods, bsp::DrawVert& v) {
    using Kind = ShaderColorMod::Kind;
    for (const ShaderColorMod& cm : mods) {
        std::array<float, 4> mult{1, 1, 1, 1}, add{0, 0, 0, 0};
        const float dot = v.normal[0] * cm.vector.x + v.normal[1] * cm.vector.y + v.normal[2] * cm.vector.z;
        const float scaled = (dot - cm.lo) / (cm.hi - cm.lo), scaled2 = (dot * dot - cm.lo) / (cm.hi - cm.lo);
        auto rgb = [&](float f) { mult[0] = mult[1] = mult[2] = f; };
        switch (cm.kind) {
            case Kind::ColorSet:
                rgb(0);
                add = {cm.vector.x * 255.0f, cm.vector.y * 255.0f, cm.vector.z * 255.0f, 0};
                break;
            case Kind::AlphaSet:
                mult[3] = 0;
                add[3] = cm.value * 255.0f;
                break;
            case Kind::ColorScale: mult = {cm.vector.x, cm.vector.y, cm.vector.z, 1}; break;
            case Kind::AlphaScale: mult[3] = cm.value; break;
            case Kind::ColorDotProduct: rgb(dot); break;
            case Kind::AlphaDotProduct: mult[3] = dot; break;
            case Kind::ColorDotProductScale: rgb(scaled); break;
            case Kind::AlphaDotProductScale: mult[3] = scaled; break;
            case Kind::ColorDotProduct2: rgb(dot * dot); break;
            case Kind::AlphaDotProduct2: mult[3] = dot * dot; break;
            case Kind::ColorDotProduct2Scale: rgb(scaled2); break;
            case Kind::AlphaDotProduct2Scale: mult[3] = scaled2; break;
            case Kind::None:
            case Kind::Volume: break;
        }
        for (size_t k = 0; k < 4; ++k) {
            const float c = mult[k] * float(v.color[k]) + add[k];
            // Clamped, then truncated like q3map2's float-to-byte store; an empty scale range (NaN) is 0.
            v.color[k] = uint8_t(c >= 255.0f ? 255.0f : (c > 0.0f ? c : 0.0f));
        }
    }
}

void applyColorMods(DrawSurface& ds) {
    if (ds.shader->colorMods.empty()) return;
    for (bsp::DrawVert& v : ds.verts) applyColorMods(ds.shader->colorMods, v);
}

std::vector<const Brush*> colorModVolumes(const BspEntity& entity) {
    std::vector<const Brush*> volumes;
    for (const Brush& b : entity.brushes)
        if (b.contentShader && b.contentShader->isColorModVolume()) volumes.push_back(&b);
    return volumes;
}

void applyVolumeColorMods(DrawSurface& ds, std::span<const Brush* const> volumes, const PlaneSet& planes) {
    if (volumes.empty() || ds.verts.empty()) return;
    DBounds surfaceBounds;
    for (const bsp::DrawVert& v : ds.verts) surfaceBounds.add(DVec3(Vec3::fromArray(v.xyz)));
    for (const Brush* b : volumes) {
        // A world volume colours every surface; a func_group's only its own.
        if (b->mapEntityNum != 0 && b->mapEntityNum != ds.mapEntityNum) continue;
        if (!b->bounds.intersects(surfaceBounds)) continue;
        for (bsp::DrawVert& v : ds.verts) {
            const bool inside = std::none_of(b->sides.begin(), b->sides.end(), [&](const BrushSide& side) {
                const MapPlane& p = planes[side.planeNum];
                const float distance = float(p.normal()[0]) * v.xyz[0] + float(p.normal()[1]) * v.xyz[1] +
                                       float(p.normal()[2]) * v.xyz[2] - float(p.dist());
                return distance > 1.0f;  // q3map2's slack: a vertex within a unit of the brush is in it
            });
            if (inside) applyColorMods(b->contentShader->colorMods, v);
        }
    }
}

void applyTcMod(DrawSurface& ds) {
    const auto& m = ds.shader->tcMod;
    for (bsp::DrawVert& v : ds.verts) {
        const float s = v.st[0], t = v.st[1];
        v.st[0] = m[0][0] * s + m[0][1] * t + m[0][2];
        v.st[1] = m[1][0] * s + m[1][1] * t + m[1][2];
    }
}

}  // namespace q3::bspstage
