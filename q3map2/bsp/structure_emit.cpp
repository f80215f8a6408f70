#include "structure_emit.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <stdexcept>

#include "brush_filter.h"
#include "script.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

// Float bounds become int by truncation; values outside the int range (the inverted bounds of a
// box that was never extended) give INT_MIN, as the x86 conversion q3map2 relies on does.
int32_t truncateToInt(double v) {
    const float f = float(v);
    if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT_MIN;
    return int32_t(f);
}

struct Emitter {
    bsp::Bsp& out;
    const LoadedMap& map;
    const ShaderTable& shaders;

    int shader(const char* name, uint32_t contentFlags, uint32_t surfaceFlags) {
        for (size_t i = 0; i < out.shaders.size(); ++i) {
            const bsp::Shader& s = out.shaders[i];
            if (uint32_t(s.surfaceFlags) == surfaceFlags && uint32_t(s.contentFlags) == contentFlags &&
                equalsNoCase(s.name, name))
                return int(i);
        }
        bsp::Shader s{};
        std::strncpy(s.name, name, sizeof s.name - 1);
        s.surfaceFlags = int32_t(surfaceFlags);
        s.contentFlags = int32_t(contentFlags);
        out.shaders.push_back(s);
        return int(out.shaders.size()) - 1;
    }
    int shader(const ShaderInfo& si) { return shader(map.shaderName(si).c_str(), si.contentFlags, si.surfaceFlags); }

    // Bevels carry no shader: q3map2 writes "noshader" with the bevel's inherited surface flags.
    int sideShader(const BrushSide& side) {
        if (side.shader) return shader(*side.shader);
        const ShaderInfo& none = shaders.find("noshader");
        return shader("noshader", none.contentFlags, side.bevel ? side.surfaceFlags : none.surfaceFlags);
    }

    void brushes(const std::vector<Brush>& list) {
        for (const Brush& b : list) {
            bsp::Brush db{};
            db.shaderNum = shader(*b.contentShader);
            db.firstSide = int32_t(out.brushSides.size());
            for (const BrushSide& side : b.sides) out.brushSides.push_back({side.planeNum, sideShader(side)});
            db.numSides = int32_t(b.sides.size());
            out.brushes.push_back(db);
        }
    }

    // Brushes were filtered in first to last and q3map2 pushes each to the front of the leaf's
    // list: the lump holds them latest first.
    void leaf(int cluster, int area, const DBounds& bounds, const std::vector<int>& brushRefs, bool opaque,
              int firstBrush, bool latestFirst = true) {
        bsp::Leaf l{};
        l.cluster = cluster;
        l.area = area;
        for (int i = 0; i < 3; ++i) {
            l.mins[i] = truncateToInt(bounds.mins[i]);
            l.maxs[i] = truncateToInt(bounds.maxs[i]);
        }
        l.firstLeafBrush = int32_t(out.leafBrushes.size());
        if (latestFirst)
            for (auto it = brushRefs.rbegin(); it != brushRefs.rend(); ++it) out.leafBrushes.push_back(firstBrush + *it);
        else
            for (int ref : brushRefs) out.leafBrushes.push_back(firstBrush + ref);
        l.numLeafBrushes = int32_t(out.leafBrushes.size()) - l.firstLeafBrush;
        if (!opaque) l.firstLeafSurface = int32_t(out.leafSurfaces.size());
        out.leafs.push_back(l);
    }

    void treeLeaf(const TreeNode& n, int firstBrush) {
        leaf(n.cluster, n.area, n.bounds, n.brushes, n.opaque, firstBrush);
    }

    void node(const Tree& tree, int index, int firstBrush) {
        const TreeNode& n = tree.node(index);
        if (n.isLeaf()) {
            treeLeaf(n, firstBrush);
            return;
        }
        if (n.planeNum & 1) throw std::logic_error("node on an odd plane");
        const size_t id = out.nodes.size();
        bsp::Node dn{};
        dn.planeNum = n.planeNum;
        for (int i = 0; i < 3; ++i) {
            dn.mins[i] = truncateToInt(n.bounds.mins[i]);
            dn.maxs[i] = truncateToInt(n.bounds.maxs[i]);
        }
        out.nodes.push_back(dn);
        for (int i = 0; i < 2; ++i) {
            const int child = n.children[i];
            if (tree.node(child).isLeaf()) {
                out.nodes[id].children[i] = -int32_t(out.leafs.size() + 1);
                treeLeaf(tree.node(child), firstBrush);
            } else {
                out.nodes[id].children[i] = int32_t(out.nodes.size());
                node(tree, child, firstBrush);
            }
        }
    }
};

// Brushes and patch control points; lightgrid brushes alone when the model has any.
DBounds modelBounds(const BspEntity& e) {
    DBounds all, lightGrid;
    for (const Brush& b : e.brushes) {
        if (b.sides.empty()) continue;
        all.add(b.bounds);
        if (b.compileFlags & compileflags::LightGrid) lightGrid.add(b.bounds);
    }
    for (const map::MapPatch* p : e.patches)
        for (const map::PatchControl& c : p->control) all.add(DVec3(c.xyz));
    return lightGrid.empty() ? all : lightGrid;
}

}  // namespace

bsp::Bsp emitStructure(LoadedMap& map, WorldStructure& world, const ShaderTable& shaders,
                       const EntityLumpOptions& entityOptions) {
    bsp::Bsp out;
    out.headerLumps = 18;  // q3map2 writes the (empty) advertisement slot too
    Emitter emit{out, map, shaders};

    // Leaf 0 stays an unused dummy with inverted bounds: children encode leaves as -(leaf + 1).
    bsp::Leaf dummy{};
    for (int i = 0; i < 3; ++i) {
        dummy.mins[i] = INT_MAX;
        dummy.maxs[i] = INT_MIN;
    }
    out.leafs.push_back(dummy);
    out.drawIndexes = {0, 1, 2, 0, 2, 3};  // q3map2 seeds the index pool with a quad

    for (size_t i = 0; i < map.entities.size(); ++i) {
        BspEntity& e = map.entities[i];
        if (e.brushes.empty() && e.patches.empty()) continue;
        bsp::Model model{};
        const DBounds bounds = modelBounds(e);
        for (int k = 0; k < 3; ++k) {
            model.mins[k] = float(bounds.mins[k]);
            model.maxs[k] = float(bounds.maxs[k]);
        }
        model.firstSurface = int32_t(out.surfaces.size());
        model.firstBrush = int32_t(out.brushes.size());
        emit.brushes(e.brushes);
        model.numBrushes = int32_t(e.brushes.size());
        if (i == 0) {
            filterDetailBrushesIntoTree(e.brushes, world.tree, map.planes);
            emit.node(world.tree, world.tree.head, model.firstBrush);
        } else {
            // Brush models get no tree: one open leaf holding every brush in entity order, with
            // the unset bounds q3map2 writes for it.
            std::vector<int> all(e.brushes.size());
            for (size_t k = 0; k < all.size(); ++k) all[k] = int(k);
            emit.leaf(0, 0, DBounds{}, all, false, model.firstBrush, false);
        }
        out.models.push_back(model);
    }

    for (int i = 0; i < map.planes.size(); ++i) {
        const DPlane& p = map.planes[i].plane;
        out.planes.push_back({{float(p.normal.x), float(p.normal.y), float(p.normal.z)}, float(p.dist)});
    }
    out.entities = bsp::unparseEntities(bspEntities(map, entityOptions));
    return out;
}

}  // namespace q3::bspstage
