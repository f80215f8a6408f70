#include "debug_portals.h"

#include <array>

#include "tree_portals.h"

namespace q3::bspstage {
namespace {

// q3map2's twelve debug colours.
constexpr std::array<std::array<uint8_t, 3>, 12> kDebugColors = {{{255, 0, 0},
                                                                  {192, 128, 128},
                                                                  {255, 255, 0},
                                                                  {192, 192, 128},
                                                                  {0, 255, 255},
                                                                  {128, 192, 192},
                                                                  {0, 0, 255},
                                                                  {128, 128, 192},
                                                                  {255, 0, 255},
                                                                  {192, 128, 192},
                                                                  {0, 255, 0},
                                                                  {128, 192, 128}}};

}  // namespace

std::vector<DrawSurface> debugPortalSurfaces(const Tree& tree, PlaneSet& planes, const ShaderTable& shaders) {
    std::vector<DrawSurface> out;
    const ShaderInfo& shader = shaders.find("debugportals");
    tree.forEachLeaf([&](int leaf) {
        if (tree.node(leaf).opaque) return;
        int place = 0;  // counts every portal of the list, written or not
        tree.forEachPortal(leaf, [&](int index) {
            const Portal& p = tree.portal(index);
            const int colour = place++ % 12;
            if (p.winding.empty() || p.nodes[0] != leaf || !portalPassable(tree, p)) return;
            DrawSurface ds;
            ds.kind = SurfaceKind::Face;
            ds.shader = &shader;
            ds.planar = true;
            ds.planeNum = planes.find(p.plane);
            ds.planeNormal = p.plane.normal.toFloat();
            ds.castShadows = 0;  // q3map2 leaves the lighting keys of these surfaces zero
            ds.receiveShadows = 0;
            for (const DVec3& point : p.winding) {
                bsp::DrawVert v{};
                point.toFloat().toArray(v.xyz);
                ds.planeNormal.toArray(v.normal);
                for (int k = 0; k < 3; ++k) v.color[k] = kDebugColors[size_t(colour)][size_t(k)];
                v.color[3] = 32;
                ds.verts.push_back(v);
            }
            out.push_back(std::move(ds));
        });
    });
    return out;
}

}  // namespace q3::bspstage
