#include "bsp_brushes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "decals/decals.h"
#include "feedback_log.h"
#include "log.h"
#include "model_numbers.h"
#include "script.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

// Brushes must lie strictly inside this box (q3map2 common/maxworld.h).
DBounds worldLimits() {
    DBounds b;
    b.add(DVec3::splat(-kMaxWorldCoord));
    b.add(DVec3::splat(kMaxWorldCoord));
    return b;
}

std::string brushLabel(const Brush& b) {
    return "Entity " + std::to_string(b.mapEntityNum) + ", Brush " + std::to_string(b.brushNum);
}

// Sides whose plane cannot be built are dropped, a repeated plane keeps its first side, and two
// opposite planes make the whole brush invalid (returns false). Each case is reported as q3map2
// reports it (on its warning stream).
bool removeDuplicatePlanes(Brush& b, FeedbackStream* feedback, Log& log) {
    auto report = [&](std::string_view problem) { reportBrushProblem(log, feedback, b.mapEntityNum, b.brushNum, problem, false); };
    for (size_t i = 0; i < b.sides.size();) {
        bool removed = false;
        if (b.sides[i].planeNum < 0) {
            report("degenerate plane");
            removed = true;
        }
        for (size_t j = 0; j < i && !removed; ++j) {
            if (b.sides[i].planeNum == b.sides[j].planeNum) {
                report("duplicate plane");
                removed = true;
            } else if (b.sides[i].planeNum == (b.sides[j].planeNum ^ 1)) {
                report("mirrored plane");
                return false;
            }
        }
        if (removed)
            b.sides.erase(b.sides.begin() + std::ptrdiff_t(i));
        else
            ++i;
    }
    return true;
}

// Only one side of an areaportal brush may be the portal: the largest keeps the flag.
void keepLargestAreaportalSide(Brush& b, Log& log) {
    int count = 0;
    BrushSide* largest = nullptr;
    double largestArea = -1;
    for (BrushSide& s : b.sides) {
        if (!(s.compileFlags & compileflags::AreaPortal)) continue;
        ++count;
        const double area = windingArea(s.winding);
        if (area > largestArea) {
            largestArea = area;
            largest = &s;
        }
    }
    if (count < 2) return;
    log.warning(brushLabel(b) + ": areaportal brush with > 1 areaportal faces");
    for (BrushSide& s : b.sides)
        if (&s != largest) s.compileFlags &= ~compileflags::AreaPortal;
}

const ShaderInfo& lookUpShader(const std::string& texture, const ShaderTable& shaders, LoadedMap& out) {
    const std::string name = map::shaderNameForTexture(texture);
    const ShaderInfo& shader = shaders.find(name);
    if (!shader.explicitScript) out.implicitShaderNames.try_emplace(&shader, name);
    return shader;
}

Brush brushFromMap(const map::MapBrush& source, int mapEntityNum, const ShaderTable& shaders, LoadedMap& out) {
    PlaneSet& planes = out.planes;
    Brush b;
    b.mapEntityNum = mapEntityNum;
    b.brushNum = source.primitiveNum;
    for (const map::BrushFace& face : source.faces) {
        BrushSide side;
        auto exact = [&](int i) { return DVec3{face.exactPoints[i][0], face.exactPoints[i][1], face.exactPoints[i][2]}; };
        const DVec3 p0 = exact(0), p1 = exact(1), p2 = exact(2);
        side.planeNum = planes.fromPoints(p0, p1, p2);
        const DVec3 normal = normalize(cross(p2 - p0, p1 - p0));
        side.exactPlane = {normal, dot(p0, normal)};
        const ShaderInfo& shader = lookUpShader(face.texture, shaders, out);
        side.shader = &shader;
        side.face = &face;
        side.contentFlags = shader.contentFlags;
        side.surfaceFlags = out.flagRules.surfaceFlags(shader);
        side.compileFlags = shader.compileFlags;
        // Of the three legacy numbers only the detail bit of the first still means something.
        if (face.hasFlags && (uint32_t(face.contentFlags) & compileflags::Detail)) side.compileFlags |= compileflags::Detail;
        b.sides.push_back(std::move(side));
    }
    return b;
}

// Moves every plane of the entity's brushes by -offset and rebuilds their windings.
void offsetBrushes(std::vector<Brush>& brushes, const DVec3& offset, PlaneSet& planes) {
    for (Brush& b : brushes) {
        for (BrushSide& side : b.sides) {
            const MapPlane& p = planes[side.planeNum];
            // In 32-bit floats, as q3map2's plane distance of the origin is.
            const float moved = float(p.dist()) - dot(p.normal().toFloat(), offset.toFloat());
            side.planeNum = planes.find({p.normal(), double(moved)});
            if (side.exactPlane.normal != DVec3{}) side.exactPlane.dist -= dot(side.exactPlane.normal, offset);
        }
        createBrushWindings(b, planes);
    }
}

}  // namespace

const std::string& LoadedMap::shaderName(const ShaderInfo& shader) const {
    auto it = implicitShaderNames.find(&shader);
    return it != implicitShaderNames.end() ? it->second : shader.name;
}

bool BspEntity::isPointEntity() const {
    return brushes.empty() && patches.empty() && !equalsNoCase(classname, "_decal");
}

DVec3 parseVectorKey(const std::string& text) {
    float v[3] = {0, 0, 0};
    std::sscanf(text.c_str(), "%f %f %f", &v[0], &v[1], &v[2]);
    return {v[0], v[1], v[2]};
}

namespace {

// The point where three planes meet (Cramer's rule); false when two of them are parallel.
bool solveThreePlanes(const DPlane& p0, const DPlane& p1, const DPlane& p2, DVec3& out) {
    const DPlane* rows[3] = {&p0, &p1, &p2};
    auto det3 = [&](auto&& at) {
        return at(0, 0) * (at(1, 1) * at(2, 2) - at(2, 1) * at(1, 2)) -
               at(0, 1) * (at(1, 0) * at(2, 2) - at(2, 0) * at(1, 2)) +
               at(0, 2) * (at(1, 0) * at(2, 1) - at(1, 1) * at(2, 0));
    };
    const double det = det3([&](int r, int c) { return rows[r]->normal[c]; });
    if (std::fabs(det) < 1e-12) return false;
    for (int axis = 0; axis < 3; ++axis)
        out[axis] = det3([&](int r, int c) { return c == axis ? rows[r]->dist : rows[r]->normal[c]; }) / det;
    return true;
}

// The box of every corner of the brush: each point where three of its planes meet that lies
// behind all of them (within 0.1), as q3map2 bounds a brush before building its windings.
DBounds brushCornerBounds(const std::vector<DPlane>& planes) {
    DBounds bounds;
    for (size_t i = 0; i < planes.size(); ++i)
        for (size_t j = i + 1; j < planes.size(); ++j)
            for (size_t k = j + 1; k < planes.size(); ++k) {
                DVec3 corner;
                if (!solveThreePlanes(planes[i], planes[j], planes[k], corner)) continue;
                if (std::all_of(planes.begin(), planes.end(),
                                [&](const DPlane& p) { return p.distanceTo(corner) < kOnEpsilon; }))
                    bounds.add(corner);
            }
    return bounds;
}

// Past this many sides a brush is bounded by its chopped windings instead: the corner search
// tries every triple of planes, which a hostile map could make take minutes per brush.
constexpr size_t kMaxSidesForCornerSearch = 96;

// Side `i`'s winding: `base` cut by every other side but its opposite and the bevels, with
// `sidePlanes` holding each side's plane (in whatever frame `base` is in).
Winding cutByOtherSides(const Brush& brush, size_t i, Winding base, const std::vector<DPlane>& sidePlanes) {
    const BrushSide& side = brush.sides[i];
    for (size_t j = 0; j < brush.sides.size() && !base.empty(); ++j) {
        const BrushSide& clipper = brush.sides[j];
        if (i == j || clipper.planeNum == (side.planeNum ^ 1) || clipper.bevel) continue;
        chopWindingInPlaceAccurate(base, sidePlanes[j].flipped(), 0);
    }
    return base;
}

// The box of the brush's windings, each cut from a world-sized base winding by the other sides.
DBounds choppedWindingBounds(const Brush& brush, const std::vector<DPlane>& sidePlanes) {
    const DBounds world{DVec3{-kMaxWorldCoord, -kMaxWorldCoord, -kMaxWorldCoord},
                        DVec3{kMaxWorldCoord, kMaxWorldCoord, kMaxWorldCoord}};
    DBounds bounds;
    for (size_t i = 0; i < brush.sides.size(); ++i) {
        if (brush.sides[i].bevel) continue;
        const Winding w = cutByOtherSides(brush, i, baseWindingForPlaneInBounds(sidePlanes[i], world), sidePlanes);
        for (const DVec3& p : w) bounds.add(p);
    }
    return bounds;
}

}  // namespace

bool createBrushWindings(Brush& brush, const PlaneSet& planes) {
    std::vector<DPlane> sidePlanes, bounding;
    for (const BrushSide& side : brush.sides) {
        sidePlanes.push_back(side.exactPlane.normal != DVec3{} ? side.exactPlane : planes[side.planeNum].plane);
        if (!side.bevel) bounding.push_back(sidePlanes.back());
    }
    DBounds corners = bounding.size() <= kMaxSidesForCornerSearch ? brushCornerBounds(bounding)
                                                                  : choppedWindingBounds(brush, sidePlanes);
    if (corners.empty()) {
        for (BrushSide& side : brush.sides) side.winding.clear();
        brush.bounds = DBounds{};
        return false;
    }
    // Windings are built around the brush's centre, from base windings that just cover its box,
    // and moved back: their first points and last bits are those of q3map2's.
    const DVec3 offset = corners.center();
    corners.mins -= offset;
    corners.maxs -= offset;
    for (DPlane& p : sidePlanes) p.dist -= dot(p.normal, offset);
    for (size_t i = 0; i < brush.sides.size(); ++i) {
        Winding w = cutByOtherSides(brush, i, baseWindingForPlaneInBounds(sidePlanes[i], corners), sidePlanes);
        weldShortEdges(w);
        BrushSide& side = brush.sides[i];
        side.winding.clear();
        if (w.size() >= 3)
            // + 0.0 turns -0 into 0, as q3map2's move back does.
            for (const DVec3& p : w) side.winding.push_back(roundToFloat(p + offset + DVec3{0.0, 0.0, 0.0}));
    }
    brush.bounds = DBounds{};
    for (const BrushSide& side : brush.sides)
        for (const DVec3& p : side.winding) brush.bounds.add(p);
    return !brush.bounds.empty() && worldLimits().surroundsStrictly(brush.bounds);
}

void setBrushContents(Brush& b, bool fullDetail, Log& log) {
    if (b.sides.empty()) return;
    uint32_t contentFlags = b.sides[0].contentFlags;
    uint32_t compileFlags = b.sides[0].compileFlags;
    b.contentShader = b.sides[0].shader;
    // The brush's content shader: the first side's, replaced in priority liquid > fog > playerclip
    // > non-solid by a later side.
    for (size_t i = 1; i < b.sides.size(); ++i) {
        const BrushSide& s = b.sides[i];
        if (!s.shader) continue;
        contentFlags |= s.contentFlags;
        compileFlags |= s.compileFlags;
        const ShaderInfo& current = *b.contentShader;
        if (current.compileFlags & compileflags::Liquid) continue;
        if (s.compileFlags & compileflags::Liquid) { b.contentShader = s.shader; continue; }
        if (current.compileFlags & compileflags::Fog) continue;
        if (s.compileFlags & compileflags::Fog) { b.contentShader = s.shader; continue; }
        if (current.contentFlags & contents::PlayerClip) continue;
        if (s.contentFlags & contents::PlayerClip) { b.contentShader = s.shader; continue; }
        if (!(current.compileFlags & compileflags::Solid)) continue;
        if (!(s.compileFlags & compileflags::Solid)) b.contentShader = s.shader;
    }
    if ((compileFlags & compileflags::Detail) && (compileFlags & compileflags::Structural)) {
        log.debug(brushLabel(b) + ": mixed detail and structural (defaulting to structural)");
        compileFlags &= ~compileflags::Detail;
    }
    if (fullDetail) compileFlags &= ~compileflags::Detail;
    // Translucent brushes not explicitly structural never take part in the structural tree.
    if ((compileFlags & compileflags::Translucent) && !(compileFlags & compileflags::Structural))
        compileFlags |= compileflags::Detail;
    b.detail = (compileFlags & compileflags::Detail) != 0;
    b.opaque = !(compileFlags & compileflags::Translucent);
    b.contentFlags = contentFlags;
    b.compileFlags = compileFlags;
}

LoadedMap loadMapForBsp(const map::MapFile& map, const ShaderTable& shaders, const MapLoadOptions& options, Log& log) {
    LoadedMap out{PlaneSet(options.epsilons), {}, {}, {}, {}, options.flagRules, {}};
    for (const map::MapEntity& source : map.entities) {
        BspEntity ent;
        ent.source = &source;
        ent.mapEntityNum = source.number;
        ent.classname = std::string(source.classname());
        if (equalsNoCase(ent.classname, "group_info")) continue;
        const bool isWorld = out.entities.empty();
        const bool isGroup = !isWorld && !options.keepGroups && equalsNoCase(ent.classname, "func_group");
        ent.origin = parseVectorKey(source.value("origin"));
        if (!options.noCurves)
            for (const map::MapPatch& p : source.patches) ent.patches.push_back({&p, source.number});
        // Shaders are looked up in file order (brushes and patches interleaved): the first
        // spelling of a shader without a script names it.
        size_t nextPatch = 0;
        auto lookUpPatchShadersBefore = [&](int primitiveNum) {
            for (; nextPatch < ent.patches.size() && ent.patches[nextPatch].patch->primitiveNum < primitiveNum; ++nextPatch)
                lookUpShader(ent.patches[nextPatch].patch->texture, shaders, out);
        };

        bool haveOriginBrush = false;
        DVec3 originBrushCenter;
        std::vector<Brush> opaque, translucent;  // opaque kept latest-first below
        for (const map::MapBrush& mb : source.brushes) {
            lookUpPatchShadersBefore(mb.primitiveNum);
            Brush b = brushFromMap(mb, source.number, shaders, out);
            if (!removeDuplicatePlanes(b, options.feedback, log)) continue;
            setBrushContents(b, options.fullDetail, log);
            if (options.noDetail && (b.compileFlags & compileflags::Detail)) continue;
            if (options.noWater && (b.compileFlags & compileflags::Liquid)) continue;
            if (options.noHint && (b.compileFlags & compileflags::Hint)) continue;
            if (!createBrushWindings(b, out.planes)) continue;
            if (b.compileFlags & compileflags::Origin) {
                if (isWorld) {
                    log.warning(brushLabel(b) + ": origin brushes not allowed in world");
                    continue;
                }
                log.info("Entity " + std::to_string(source.number) + " (" + ent.classname + "), Brush " +
                         std::to_string(b.brushNum) + ": origin brush detected");
                originBrushCenter = b.bounds.center();
                haveOriginBrush = true;
                continue;
            }
            if ((b.compileFlags & compileflags::AreaPortal) && !isWorld && !isGroup) {
                log.warning("Entity " + std::to_string(source.number) + " (" + ent.classname + "), Brush " +
                            std::to_string(b.brushNum) + ": areaportals only allowed in world");
                continue;
            }
            if (b.compileFlags & compileflags::AreaPortal) keepLargestAreaportalSide(b, log);
            if (!options.keepGroups) {
                auto [box, edge] = addBrushBevels(b, out.planes, options.bevelSnap);
                out.counts.boxBevels += box;
                out.counts.edgeBevels += edge;
            }
            if (b.compileFlags & compileflags::AreaPortal) ++out.counts.areaportals;
            (b.opaque ? opaque : translucent).push_back(std::move(b));
        }
        lookUpPatchShadersBefore(source.primitiveCount());
        // q3map2 links each patch in front of the entity's list.
        std::reverse(ent.patches.begin(), ent.patches.end());
        for (auto it = opaque.rbegin(); it != opaque.rend(); ++it) ent.brushes.push_back(std::move(*it));
        for (Brush& b : translucent) ent.brushes.push_back(std::move(b));

        if (haveOriginBrush) {
            ent.hasOriginBrush = true;
            ent.originBrushCenter = originBrushCenter;
            ent.origin = ent.origin + originBrushCenter;
            offsetBrushes(ent.brushes, originBrushCenter, out.planes);
        }
        if (isGroup) {
            // func_group is an editor convenience: its brushes belong to the world, shifted by
            // the group's own origin key. Without one the planes stay as found: looking them up
            // again could land on a neighbouring plane within the epsilons, which q3map2 does not.
            if (ent.origin != DVec3{}) offsetBrushes(ent.brushes, -ent.origin, out.planes);
            std::vector<Brush>& world = out.entities.front().brushes;
            std::vector<Brush> head;
            for (Brush& b : ent.brushes) {
                if (b.opaque)
                    head.insert(head.begin(), std::move(b));
                else
                    world.push_back(std::move(b));
            }
            world.insert(world.begin(), std::make_move_iterator(head.begin()), std::make_move_iterator(head.end()));
            // q3map2 prepends the group's patches to the world's.
            std::vector<PatchRef>& worldPatches = out.entities.front().patches;
            worldPatches.insert(worldPatches.begin(), ent.patches.begin(), ent.patches.end());
            continue;
        }
        out.entities.push_back(std::move(ent));
    }
    if (out.entities.empty()) throw CompileError(map.name + ": no entities (a map needs a worldspawn)");
    const BspEntity& world = out.entities.front();
    for (const Brush& b : world.brushes) {
        ++out.counts.worldBrushes;
        if (b.detail) ++out.counts.detailBrushes;
        out.worldBounds.add(b.bounds);
    }
    if (options.decals) collectDecalEntities(out, map, log);
    numberModels(out, options.resolveClones, log);
    for (const BspEntity& e : out.entities) out.counts.patches += int(e.patches.size());
    return out;
}

}  // namespace q3::bspstage
