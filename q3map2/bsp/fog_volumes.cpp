#include "fog_volumes.h"

#include <algorithm>
#include <cstring>

#include "log.h"
#include "patch_split.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

DBounds surfaceBounds(const DrawSurface& ds) {
    DBounds b;
    for (const bsp::DrawVert& v : ds.verts) b.add(DVec3(Vec3::fromArray(v.xyz)));
    return b;
}

const Brush& fogBrush(const MapFog& fog, const LoadedMap& map) {
    return map.entities[size_t(fog.entity)].brushes[size_t(fog.brush)];
}

// Cuts face `index` by the fog brush, the inside piece replacing it and the outside pieces appended:
// false (untouched) when no part is inside or the face lies on a side facing out of the volume.
bool chopFace(size_t index, std::vector<DrawSurface>& surfaces, const Brush& volume, const LoadedMap& map,
              const FaceContext& context, const std::vector<EntitySurfaceParams>& paramsByMapEntity,
              FogCounts& counts) {
    const DrawSurface ds = surfaces[index];
    if (ds.brush < 0) return false;
    const BspEntity& world = map.entities.front();
    const int facePlane = world.brushes[size_t(ds.brush)].sides[size_t(ds.side)].planeNum ^ (ds.fogBackFace ? 1 : 0);
    Winding w;
    for (const bsp::DrawVert& v : ds.verts) w.push_back(DVec3(Vec3::fromArray(v.xyz)));
    std::vector<Winding> outside;
    for (const BrushSide& side : volume.sides) {
        if (facePlane == side.planeNum) return false;     // on the volume's surface, facing out
        if ((facePlane ^ 1) == side.planeNum) continue;   // on it facing in: stays inside
        auto [front, back] = clipWindingStrict(w, context.planes[side.planeNum].plane, kOnEpsilon);
        if (back.empty()) return false;
        if (!front.empty()) outside.push_back(std::move(front));
        w = std::move(back);
    }
    const EntitySurfaceParams& params = paramsByMapEntity[size_t(ds.mapEntityNum)];
    counts.faceFragments += int(outside.size());
    for (const Winding& piece : outside) {
        DrawSurface fragment = faceSurface(world, ds.brush, ds.side, piece, params, context, ds.fogBackFace);
        fragment.fogNum = ds.fogNum;
        surfaces.push_back(std::move(fragment));
    }
    // The inside piece is made from the side again, so that it is snapped like every face.
    surfaces[index] = faceSurface(world, ds.brush, ds.side, w, params, context, ds.fogBackFace);
    return true;
}

PatchGrid gridOf(const DrawSurface& ds) { return {ds.patchWidth, ds.patchHeight, ds.verts}; }

void setGrid(DrawSurface& ds, PatchGrid grid) {
    ds.patchWidth = grid.width;
    ds.patchHeight = grid.height;
    ds.verts = std::move(grid.verts);
}

// Cuts a patch by the volume's bottom and top planes only (sides 4 and 5).
bool chopPatch(size_t index, std::vector<DrawSurface>& surfaces, const Brush& volume, const PlaneSet& planes,
               FogCounts& counts) {
    PatchGrid grid = gridOf(surfaces[index]);
    std::vector<PatchGrid> outside;
    for (int i = 4; i <= 5; ++i) {
        GridSplit split = splitGridByPlane(std::move(grid), planes[volume.sides[size_t(i)].planeNum].plane);
        if (!split.back) return false;
        grid = std::move(*split.back);
        if (split.front) outside.push_back(std::move(*split.front));
    }
    counts.patchFragments += int(outside.size());
    for (PatchGrid& piece : outside) {
        PatchGrid turned = transposeGrid(piece);
        invertGrid(turned);
        DrawSurface copy = surfaces[index];
        setGrid(copy, std::move(turned));
        surfaces.push_back(std::move(copy));
    }
    if (!outside.empty()) {
        PatchGrid turned = transposeGrid(grid);
        invertGrid(turned);
        setGrid(surfaces[index], std::move(turned));
    }
    return true;
}

}  // namespace

MapFogs createMapFogs(const LoadedMap& map, const ShaderTable& shaders, Log& log) {
    MapFogs out;
    for (size_t e = 0; e < map.entities.size(); ++e) {
        const std::vector<Brush>& brushes = map.entities[e].brushes;
        for (size_t b = 0; b < brushes.size(); ++b) {
            const ShaderInfo* shader = brushes[b].contentShader;
            if (!shader || !shader->fogParms) continue;
            MapFog fog{shader, int(e), int(b), -1};
            if (shader->fogDir) {
                // The visible side is the one facing most against the fog direction.
                const DVec3 dir(*shader->fogDir);
                double best = 0;
                for (size_t s = 0; s < brushes[b].sides.size(); ++s) {
                    if (brushes[b].sides[s].bevel) continue;
                    const double d = dot(dir, map.planes[brushes[b].sides[s].planeNum].normal());
                    if (d < best) {
                        best = d;
                        fog.visibleSide = int(s);
                    }
                }
            }
            out.fogs.push_back(fog);
        }
    }
    const map::MapEntity& world = *map.entities.front().source;
    const std::string* global = world.find("_fog");
    if (!global) global = world.find("fog");
    if (global) {
        log.debug("Map has global fog shader " + *global);
        const ShaderInfo* shader = shaders.findExplicit(*global);
        if (!shader) throw CompileError("Invalid shader \"" + *global + "\" referenced trying to add global fog");
        out.fogs.push_back({shader, -1, -1, -1});
        out.defaultFog = int(out.fogs.size()) - 1;
    }
    log.debug(std::to_string(out.fogs.size()) + " fogs");
    return out;
}

FogCounts fogWorldSurfaces(std::vector<DrawSurface>& surfaces, const MapFogs& fogs, const LoadedMap& map,
                           const FaceContext& context, const std::vector<EntitySurfaceParams>& paramsByMapEntity) {
    FogCounts counts;
    for (size_t fogNum = 0; fogNum < fogs.fogs.size(); ++fogNum) {
        const MapFog& fog = fogs.fogs[fogNum];
        // Pieces cut off by this fog are not cut by it again.
        const size_t base = surfaces.size();
        for (size_t i = 0; i < base; ++i) {
            if (surfaces[i].shader->noFog) continue;
            bool fogged = false;
            if (fog.entity < 0) {
                if (surfaces[i].fogNum > kNoFog) continue;  // a volume's fog wins over the global one
                fogged = true;
            } else {
                const Brush& volume = fogBrush(fog, map);
                if (!surfaceBounds(surfaces[i]).intersects(volume.bounds)) continue;
                switch (surfaces[i].kind) {
                    case SurfaceKind::Face:
                        fogged = chopFace(i, surfaces, volume, map, context, paramsByMapEntity, counts);
                        break;
                    case SurfaceKind::Patch:
                        fogged = chopPatch(i, surfaces, volume, context.planes, counts);
                        break;
                    case SurfaceKind::Triangles:
                    case SurfaceKind::ForcedMeta:
                    case SurfaceKind::Meta:
                        fogged = true;
                        break;
                    default:
                        break;
                }
            }
            if (fogged) {
                ++counts.fogged;
                surfaces[i].fogNum = int(fogNum);
            }
        }
    }
    return counts;
}

int fogForBounds(const DBounds& bounds, const MapFogs& fogs, const LoadedMap& map, double epsilon) {
    int fogNum = fogs.defaultFog;
    float bestVolume = 0;
    for (size_t i = 0; i < fogs.fogs.size(); ++i) {
        const MapFog& fog = fogs.fogs[i];
        if (fog.entity < 0) {
            fogNum = int(i);
            continue;
        }
        DBounds volume = fogBrush(fog, map).bounds;
        volume.mins -= DVec3::splat(epsilon);
        volume.maxs += DVec3::splat(epsilon);
        if (!bounds.intersects(volume)) continue;
        float overlap = 1;
        for (int k = 0; k < 3; ++k)
            overlap *= std::max(1.0f, float(std::min(bounds.maxs[k], volume.maxs[k]) - std::max(bounds.mins[k], volume.mins[k])));
        if (overlap > bestVolume) {
            bestVolume = overlap;
            fogNum = int(i);
        }
    }
    return fogNum;
}

void emitFogs(const MapFogs& fogs, const LoadedMap& map, const std::vector<int>& brushOutputs, BspBuilder& builder,
              Log& log) {
    bsp::Bsp& out = builder.bsp();
    for (size_t i = 0; i < fogs.fogs.size(); ++i) {
        const MapFog& fog = fogs.fogs[i];
        bsp::Fog f{};
        std::strncpy(f.shader, map.shaderName(*fog.shader).c_str(), sizeof f.shader - 1);
        f.brushNum = -1;
        f.visibleSide = -1;
        if (fog.entity >= 0) {
            f.brushNum = brushOutputs[size_t(fog.entity)] + fog.brush;
            if (fog.visibleSide >= 0) {
                f.visibleSide = fog.visibleSide;
            } else {
                const Brush& volume = fogBrush(fog, map);
                auto visible = [&](size_t s) {
                    const BrushSide& side = volume.sides[s];
                    return !side.visibleHull.empty() && !(side.compileFlags & compileflags::NoDraw);
                };
                // +Z first, then -Z and the others: a fogged pit is the likeliest case.
                for (size_t s = std::min<size_t>(6, volume.sides.size()); s-- > 0 && f.visibleSide < 0;)
                    if (visible(s)) f.visibleSide = int(s);
                for (size_t s = 6; s < volume.sides.size() && f.visibleSide < 0; ++s)
                    if (visible(s)) f.visibleSide = int(s);
                if (f.visibleSide >= 0) log.info("Fog " + std::to_string(i) + " has visible side " + std::to_string(f.visibleSide));
            }
        }
        out.fogs.push_back(f);
    }
    if (fogs.fogs.size() > 31)
        log.warning("MAX_IBSP_FOGS (31) exceeded (" + std::to_string(fogs.fogs.size()) +
                    "). Visual inconsistencies are expected.");
}

}  // namespace q3::bspstage
