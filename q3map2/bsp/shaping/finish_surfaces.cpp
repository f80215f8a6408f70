#include "finish_surfaces.h"

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
        auto [it, added] = celByEntity.try_emplace(surfaces[i].mapEntityNum, nullptr);
        if (added) it->second = celShaderOf(surfaces[i].mapEntityNum, in);
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

void applyTcMod(DrawSurface& ds) {
    const auto& m = ds.shader->tcMod;
    for (bsp::DrawVert& v : ds.verts) {
        const float s = v.st[0], t = v.st[1];
        v.st[0] = m[0][0] * s + m[0][1] * t + m[0][2];
        v.st[1] = m[1][0] * s + m[1][1] * t + m[1][2];
    }
}

}  // namespace q3::bspstage
