#include "bsp_builder.h"

#include <array>
#include <climits>
#include <cstring>
#include <stdexcept>

#include "script.h"
#include "shader_info.h"
#include "shaping/autosprite2.h"
#include "surface_triangles.h"

namespace q3::bspstage {
namespace {

// Float bounds become int by truncation; values outside the int range (the inverted bounds of a
// box that was never extended) give INT_MIN, as the x86 conversion q3map2 relies on does.
int32_t truncateToInt(double v) {
    const float f = float(v);
    if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT_MIN;
    return int32_t(f);
}

bool isLightGridBrush(const Brush& b) { return (b.compileFlags & compileflags::LightGrid) != 0; }

// -debuginset: each triangle, in index order, pulls its corners one unit towards its centre (a
// vertex shared by several triangles moves once per triangle), so the triangles show apart.
void insetTriangles(DrawSurface& ds) {
    for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) {
        float* corner[3];
        for (int k = 0; k < 3; ++k) corner[k] = ds.verts[size_t(ds.indexes[i + size_t(k)])].xyz;
        const Vec3 centre = (Vec3::fromArray(corner[0]) + Vec3::fromArray(corner[1]) + Vec3::fromArray(corner[2])) / 3.0f;
        for (float* c : corner) {
            // Normalised in double precision, as q3map2's VectorNormalize does.
            const DVec3 toCentre(centre - Vec3::fromArray(c));
            const double len = length(toCentre);
            const Vec3 step = len == 0 ? Vec3{0, 0, 0} : (toCentre / len).toFloat();
            (Vec3::fromArray(c) + step).toArray(c);
        }
    }
}

// -debugsurfaces: q3map2's twelve colours, by draw surface number.
constexpr uint8_t kDebugColors[12][3] = {{255, 0, 0},   {192, 128, 128}, {255, 255, 0}, {192, 192, 128},
                                         {0, 255, 255}, {128, 192, 192}, {0, 0, 255},   {128, 128, 192},
                                         {255, 0, 255}, {192, 128, 192}, {0, 255, 0},   {128, 192, 128}};

}  // namespace

BspBuilder::BspBuilder(const LoadedMap& map, const ShaderTable& shaders) : map_(map), shaders_(shaders) {
    out_.headerLumps = 18;  // q3map2 writes the (empty) advertisement slot too
    // Leaf 0 stays an unused dummy with inverted bounds: children encode leaves as -(leaf + 1).
    bsp::Leaf dummy{};
    for (int i = 0; i < 3; ++i) {
        dummy.mins[i] = INT_MAX;
        dummy.maxs[i] = INT_MIN;
    }
    out_.leafs.push_back(dummy);
    out_.drawIndexes = {0, 1, 2, 0, 2, 3};  // q3map2 seeds the index pool with a quad
}

int BspBuilder::shader(const char* name, uint32_t contentFlags, uint32_t surfaceFlags) {
    for (size_t i = 0; i < out_.shaders.size(); ++i) {
        const bsp::Shader& s = out_.shaders[i];
        if (uint32_t(s.surfaceFlags) == surfaceFlags && uint32_t(s.contentFlags) == contentFlags &&
            equalsNoCase(s.name, name))
            return int(i);
    }
    bsp::Shader s{};
    std::strncpy(s.name, name, sizeof s.name - 1);
    s.surfaceFlags = int32_t(surfaceFlags);
    s.contentFlags = int32_t(contentFlags);
    out_.shaders.push_back(s);
    return int(out_.shaders.size()) - 1;
}

int BspBuilder::shader(const ShaderInfo& si) {
    auto [it, added] = shaderEntries_.try_emplace(&si, 0);
    if (added) it->second = shader(map_.shaderName(si).c_str(), si.contentFlags, map_.flagRules.surfaceFlags(si));
    return it->second;
}

void BspBuilder::beginModel(const BspEntity& e) {
    DBounds all, lightGrid;
    for (const Brush& b : e.brushes) {
        if (b.sides.empty()) continue;
        all.add(b.bounds);
        if (isLightGridBrush(b)) lightGrid.add(b.bounds);
    }
    for (const PatchRef& p : e.patches)
        for (const map::PatchControl& c : p.patch->control) all.add(DVec3(c.xyz));
    const DBounds& bounds = lightGrid.empty() ? all : lightGrid;
    bsp::Model model{};
    for (int k = 0; k < 3; ++k) {
        model.mins[k] = float(bounds.mins[k]);
        model.maxs[k] = float(bounds.maxs[k]);
    }
    model.firstSurface = int32_t(out_.surfaces.size());
    model.firstBrush = int32_t(out_.brushes.size());
    out_.models.push_back(model);
}

void BspBuilder::emitBrushes(const std::vector<Brush>& brushes) {
    firstBrush_ = int(out_.brushes.size());
    for (const Brush& b : brushes) {
        bsp::Brush db{};
        db.shaderNum = shader(*b.contentShader);
        db.firstSide = int32_t(out_.brushSides.size());
        for (const BrushSide& side : b.sides) {
            int shaderNum;
            if (side.shader) {
                shaderNum = shader(*side.shader);
            } else {
                // Bevels carry no shader: "noshader" with the bevel's inherited surface flags.
                const ShaderInfo& none = shaders_.find("noshader");
                shaderNum = shader("noshader", none.contentFlags,
                                   side.bevel ? side.surfaceFlags : map_.flagRules.surfaceFlags(none));
            }
            out_.brushSides.push_back({side.planeNum, shaderNum});
        }
        db.numSides = int32_t(b.sides.size());
        out_.brushes.push_back(db);
    }
    bsp::Model& model = out_.models.back();
    model.firstBrush = firstBrush_;
    model.numBrushes = int32_t(brushes.size());
}

int BspBuilder::findIndexRun(const std::vector<int>& indexes) {
    // Keep the run table in step with the pool, then look for the earliest identical run.
    const std::vector<int32_t>& pool = out_.drawIndexes;
    for (; indexedUpTo_ + 3 <= pool.size(); ++indexedUpTo_)
        indexRuns_[{pool[indexedUpTo_], pool[indexedUpTo_ + 1], pool[indexedUpTo_ + 2]}].push_back(int(indexedUpTo_));
    if (indexes.size() < 3 || pool.size() < indexes.size()) return -1;
    auto it = indexRuns_.find({indexes[0], indexes[1], indexes[2]});
    if (it == indexRuns_.end()) return -1;
    for (int start : it->second) {
        if (size_t(start) + indexes.size() > pool.size()) break;
        if (std::equal(indexes.begin(), indexes.end(), pool.begin() + start)) return start;
    }
    return -1;
}

int BspBuilder::emitSurface(DrawSurface& ds, const SurfaceEmitOptions& options, int mapSurfaceNumber) {
    const ShaderInfo& si = *ds.shader;
    const int number = int(out_.surfaces.size());
    bsp::Surface s{};
    const bool flare = ds.kind == SurfaceKind::Flare || ds.kind == SurfaceKind::Shader;
    if (options.debugSurfaces && !flare)
        s.shaderNum = shader(shaders_.find("debugsurfaces"));
    else if (ds.extraSurfaceFlags == 0)
        s.shaderNum = shader(si);
    else
        s.shaderNum = shader(map_.shaderName(si).c_str(), si.contentFlags,
                             map_.flagRules.surfaceFlags(si) | ds.extraSurfaceFlags);
    s.fogNum = ds.fogNum;
    s.lightmapNum = bsp::kLightmapByVertex;
    if (flare) {
        // A flare has no vertices: its origin, colour and normal travel in the lightmap fields.
        // A shader-only surface is written the same way, with all three zero.
        s.surfaceType = bsp::MST_FLARE;
        ds.flareOrigin.toArray(s.lightmapOrigin);
        ds.flareColor.toArray(s.lightmapVecs[0]);
        ds.planeNormal.toArray(s.lightmapVecs[2]);
        out_.surfaces.push_back(s);
        ds.outputNum = number;
        return number;
    }
    if (ds.kind == SurfaceKind::Patch) {
        if (si.invert || ds.backSide) {
            for (bsp::DrawVert& v : ds.verts)
                for (float& c : v.normal) c = -c;
            for (int y = 0; y < ds.patchHeight; ++y)
                std::reverse(ds.verts.begin() + y * ds.patchWidth, ds.verts.begin() + (y + 1) * ds.patchWidth);
            ds.planeNormal = -ds.planeNormal;
        }
        s.surfaceType = bsp::MST_PATCH;
        s.patchWidth = ds.patchWidth;
        s.patchHeight = ds.patchHeight;
        for (int k = 0; k < 3; ++k) {
            s.lightmapVecs[0][k] = float(ds.lodBounds.mins[k]);
            s.lightmapVecs[1][k] = float(ds.lodBounds.maxs[k]);
        }
    } else {
        if (si.invert || ds.backSide) {
            for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) std::swap(ds.indexes[i], ds.indexes[i + 1]);
            for (bsp::DrawVert& v : ds.verts)
                for (float& c : v.normal) c = -c;
            ds.planeNormal = -ds.planeNormal;
        }
        if (si.autosprite2)
            if (std::string why = fixAutosprite2(ds); !why.empty()) warnings_.push_back(std::move(why));
        const bool soup = (ds.lightmapAxis == Vec3{0, 0, 0} && !ds.planar) || ds.kind == SurfaceKind::Triangles ||
                          ds.kind == SurfaceKind::Foghull || int(ds.verts.size()) > options.maxLightmappedVerts ||
                          options.debugSurfaces;
        s.surfaceType = soup ? bsp::MST_TRIANGLE_SOUP : bsp::MST_PLANAR;
        if (ds.kind == SurfaceKind::Foliage) {
            // Instanced by the engine: the copy count and the model's vertex count.
            s.surfaceType = bsp::MST_FOLIAGE;
            s.patchWidth = ds.patchWidth;
            s.patchHeight = ds.patchHeight;
        }
        if (options.debugInset) insetTriangles(ds);
        if (ds.indexes.size() > 16 && !si.autosprite) optimizeForVertexCache(ds.indexes);
    }
    if (ds.planar) ds.planeNormal.toArray(s.lightmapVecs[2]);

    s.firstVert = int32_t(out_.drawVerts.size());
    s.numVerts = int32_t(ds.verts.size());
    bsp::Model& model = out_.models.back();
    const bool brushModel = out_.models.size() > 1;
    for (bsp::DrawVert v : ds.verts) {
        if (si.vertexOffset != 0)
            for (int k = 0; k < 3; ++k) v.xyz[k] += v.normal[k] * si.vertexOffset;
        // World bounds stay those of its brushes (they size the light grid); brush models grow.
        if (brushModel)
            for (int k = 0; k < 3; ++k) {
                model.mins[k] = std::min(model.mins[k], v.xyz[k]);
                model.maxs[k] = std::max(model.maxs[k], v.xyz[k]);
            }
        if (options.debugSurfaces) std::memcpy(v.color, kDebugColors[mapSurfaceNumber % 12], 3);
        out_.drawVerts.push_back(v);
    }
    const int run = findIndexRun(ds.indexes);
    s.numIndexes = int32_t(ds.indexes.size());
    if (run >= 0) {
        s.firstIndex = run;
    } else {
        s.firstIndex = int32_t(out_.drawIndexes.size());
        out_.drawIndexes.insert(out_.drawIndexes.end(), ds.indexes.begin(), ds.indexes.end());
    }
    out_.surfaces.push_back(s);
    ds.outputNum = number;
    return number;
}

void BspBuilder::fixBrushSides(const std::vector<DrawSurface>& surfaces) {
    for (const DrawSurface& ds : surfaces) {
        if (ds.outputNum < 0) continue;
        const std::string& name = map_.shaderName(*ds.shader);
        auto fix = [&](const SideRef& ref) {
            if (ref.brush < 0) return;
            const bsp::Brush& brush = out_.brushes[size_t(firstBrush_ + ref.brush)];
            // q3map2's copy of a fog side for the back face was never written, and its output
            // number is still 0: the file's first brush side takes that face's shader.
            bsp::BrushSide& side = out_.brushSides[ref.fogBackFace ? 0 : size_t(brush.firstSide + ref.side)];
            if (std::strncmp(out_.shaders[size_t(side.shaderNum)].name, name.c_str(), sizeof(bsp::Shader::name)) != 0)
                side.shaderNum = shader(*ds.shader);
        };
        fix({ds.brush, ds.side, ds.fogBackFace});
        for (const SideRef& ref : ds.metaSides) fix(ref);
    }
}

void BspBuilder::leaf(const TreeNode& n) {
    bsp::Leaf l{};
    l.cluster = n.cluster;
    l.area = n.area;
    for (int i = 0; i < 3; ++i) {
        l.mins[i] = truncateToInt(n.bounds.mins[i]);
        l.maxs[i] = truncateToInt(n.bounds.maxs[i]);
    }
    l.firstLeafBrush = int32_t(out_.leafBrushes.size());
    // Brushes were filtered in first to last and q3map2 pushes each to the front of the leaf's list.
    for (auto it = n.brushes.rbegin(); it != n.brushes.rend(); ++it) out_.leafBrushes.push_back(firstBrush_ + *it);
    l.numLeafBrushes = int32_t(out_.leafBrushes.size()) - l.firstLeafBrush;
    if (!n.opaque) {
        l.firstLeafSurface = int32_t(out_.leafSurfaces.size());
        out_.leafSurfaces.insert(out_.leafSurfaces.end(), n.drawSurfaces.begin(), n.drawSurfaces.end());
        l.numLeafSurfaces = int32_t(out_.leafSurfaces.size()) - l.firstLeafSurface;
    }
    out_.leafs.push_back(l);
}

void BspBuilder::node(const Tree& tree, int index) {
    const TreeNode& n = tree.node(index);
    if (n.isLeaf()) {
        leaf(n);
        return;
    }
    if (n.planeNum & 1) throw std::logic_error("node on an odd plane");
    const size_t id = out_.nodes.size();
    bsp::Node dn{};
    dn.planeNum = n.planeNum;
    for (int i = 0; i < 3; ++i) {
        dn.mins[i] = truncateToInt(n.bounds.mins[i]);
        dn.maxs[i] = truncateToInt(n.bounds.maxs[i]);
    }
    out_.nodes.push_back(dn);
    for (int i = 0; i < 2; ++i) {
        const int child = n.children[i];
        if (tree.node(child).isLeaf()) {
            out_.nodes[id].children[i] = -int32_t(out_.leafs.size() + 1);
            leaf(tree.node(child));
        } else {
            out_.nodes[id].children[i] = int32_t(out_.nodes.size());
            node(tree, child);
        }
    }
}

void BspBuilder::endModel(const Tree& tree) {
    node(tree, tree.head);
    bsp::Model& model = out_.models.back();
    model.numSurfaces = int32_t(out_.surfaces.size()) - model.firstSurface;
}

void BspBuilder::emitPlanes(const PlaneSet& planes) {
    for (int i = 0; i < planes.size(); ++i) {
        const DPlane& p = planes[i].plane;
        out_.planes.push_back({{float(p.normal.x), float(p.normal.y), float(p.normal.z)}, float(p.dist)});
    }
}

}  // namespace q3::bspstage
