#include "surface_filter.h"

#include <algorithm>
#include <array>
#include <limits>

#include "shader_info.h"
#include "winding.h"

namespace q3::bspstage {
namespace {

// q3map2 AddReferenceToLeaf: open leaves only, once per surface.
int referenceLeaf(TreeNode& leaf, DrawSurface& ds, int outputNum) {
    if (leaf.opaque) return 0;
    if (!leaf.drawSurfaces.empty() && leaf.drawSurfaces.back() == outputNum) return 0;
    leaf.drawSurfaces.push_back(outputNum);
    if (leaf.skybox) ds.skybox = true;
    if (ds.shader && ds.shader->isSky()) leaf.sky = true;
    return 1;
}

struct Filter {
    Tree& tree;
    const PlaneSet& planes;
    DrawSurface& ds;
    int outputNum;

    int reference(int node) { return referenceLeaf(tree.node(node), ds, outputNum); }

    int winding(const Winding& w, int node) {
        const TreeNode& n = tree.node(node);
        if (n.isLeaf()) return reference(node);
        // A surface on the node's plane goes to the side it faces.
        if (ds.planeNum >= 0) {
            if (ds.planeNum == n.planeNum) return winding(w, n.children[0]);
            if (ds.planeNum == (n.planeNum ^ 1)) return winding(w, n.children[1]);
        }
        // Whole windings go down unclipped; only crossing ones are split (no copies on the way).
        switch (windingOnPlaneSide(w, planes[n.planeNum].plane)) {
        case PlaneSide::Front: return winding(w, n.children[0]);
        case PlaneSide::Back: return winding(w, n.children[1]);
        case PlaneSide::On:
        {
            // Lying on the plane: better too many references than too few.
            const int refs = winding(w, n.children[0]);
            return refs + winding(w, n.children[1]);
        }
        case PlaneSide::Cross: break;
        }
        auto [front, back] = clipWindingStrict(w, planes[n.planeNum].plane, kOnEpsilon);
        int refs = 0;
        if (!front.empty()) refs += winding(front, n.children[0]);
        if (!back.empty()) refs += winding(back, n.children[1]);
        return refs;
    }

    // Every open leaf (q3map2 AddReferenceToTree_r): the fog hull is seen from everywhere.
    int everyLeaf(int node) {
        const TreeNode& n = tree.node(node);
        if (n.isLeaf()) return reference(node);
        return everyLeaf(n.children[0]) + everyLeaf(n.children[1]);
    }

    int point(const DVec3& p, int node) {
        const TreeNode& n = tree.node(node);
        if (n.isLeaf()) return reference(node);
        const double d = planes[n.planeNum].plane.distanceTo(p);
        int refs = 0;
        if (d >= -kOnEpsilon) refs += point(p, n.children[0]);
        if (d <= kOnEpsilon) refs += point(p, n.children[1]);
        return refs;
    }

    int hull(const std::array<DVec3, 16>& points, int node) {
        const TreeNode& n = tree.node(node);
        if (n.isLeaf()) return reference(node);
        double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
        for (const DVec3& p : points) {
            const double d = float(planes[n.planeNum].plane.distanceTo(p));
            lo = std::min(lo, d);
            hi = std::max(hi, d);
        }
        int refs = 0;
        if (hi >= -kOnEpsilon) refs += hull(points, n.children[0]);
        if (lo <= kOnEpsilon) refs += hull(points, n.children[1]);
        return refs;
    }
};

DVec3 pointOf(const bsp::DrawVert& v) { return DVec3(xyzOf(v)); }
Vec3 mid(Vec3 a, Vec3 b) { return (a + b) * 0.5f; }

// Points whose convex hull holds every tessellation of one 3x3 sub-patch: its four corners and
// the points the engine's subdivision would place on its edges and centre.
std::array<DVec3, 16> subPatchHull(const DrawSurface& ds, int x, int y) {
    auto p = [&](int dx, int dy) { return Vec3::fromArray(ds.verts[size_t((y + dy) * ds.patchWidth + x + dx)].xyz); };
    std::array<Vec3, 16> q{p(0, 0), p(2, 0), p(0, 2), p(2, 2),
                           mid(p(0, 0), p(1, 0)), mid(p(1, 0), p(2, 0)), mid(p(0, 2), p(1, 2)), mid(p(1, 2), p(2, 2)),
                           mid(p(0, 0), p(0, 1)), mid(p(0, 1), p(0, 2)), mid(p(2, 0), p(2, 1)), mid(p(2, 1), p(2, 2))};
    const Vec3 top = mid(q[4], q[5]), bottom = mid(q[6], q[7]), left = mid(q[8], q[9]), right = mid(q[10], q[11]);
    const Vec3 centreColumn = (p(1, 0) + p(1, 1) * 2 + p(1, 2)) * 0.25f;  // columns are blended first
    q[12] = mid(left, centreColumn);
    q[13] = mid(centreColumn, right);
    const Vec3 centre = mid(q[12], q[13]);
    // The centre control point as if the column blend had come last and produced `centre`.
    const Vec3 centreRow = centre * 2 - mid(top, bottom);
    q[14] = mid(top, centreRow);
    q[15] = mid(centreRow, bottom);
    std::array<DVec3, 16> out;
    for (size_t i = 0; i < q.size(); ++i) out[i] = DVec3(q[i]);
    return out;
}

}  // namespace

int addSkyboxReferences(DrawSurface& ds, Tree& tree, int outputNum) {
    int refs = 0;
    tree.forEachLeaf([&](int n) {
        TreeNode& leaf = tree.node(n);
        if (!leaf.sky) return;
        for (const bsp::DrawVert& v : ds.verts) leaf.bounds.add(pointOf(v));
        refs += referenceLeaf(leaf, ds, outputNum);
    });
    return refs;
}

int filterSurfaceIntoTree(DrawSurface& ds, Tree& tree, const PlaneSet& planes, int outputNum) {
    Filter f{tree, planes, ds, outputNum};
    switch (ds.kind) {
        case SurfaceKind::Face:
        case SurfaceKind::Decal: {
            Winding w;
            for (const bsp::DrawVert& v : ds.verts) w.push_back(pointOf(v));
            return f.winding(w, tree.head);
        }
        case SurfaceKind::Patch: {
            int refs = 0;
            for (int y = 0; y + 2 < ds.patchHeight; y += 2)
                for (int x = 0; x + 2 < ds.patchWidth; x += 2) refs += f.hull(subPatchHull(ds, x, y), tree.head);
            return refs;
        }
        case SurfaceKind::Triangles:
        case SurfaceKind::ForcedMeta:
        case SurfaceKind::Meta: {
            int refs = 0;
            for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) {
                Winding w{pointOf(ds.verts[size_t(ds.indexes[i])]), pointOf(ds.verts[size_t(ds.indexes[i + 1])]),
                          pointOf(ds.verts[size_t(ds.indexes[i + 2])])};
                refs += f.winding(w, tree.head);
            }
            for (const bsp::DrawVert& v : ds.verts) refs += f.point(pointOf(v), tree.head);
            return refs;
        }
        case SurfaceKind::Foliage: {
            // Every copy: the model's triangles and vertices moved to the copy's place.
            int refs = 0;
            const size_t modelVerts = size_t(ds.patchHeight);
            for (size_t c = modelVerts; c < ds.verts.size(); ++c) {
                const Vec3 at = xyzOf(ds.verts[c]);
                auto moved = [&](size_t v) { return DVec3(at + xyzOf(ds.verts[v])); };  // summed in floats
                for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) {
                    Winding w{moved(size_t(ds.indexes[i])), moved(size_t(ds.indexes[i + 1])), moved(size_t(ds.indexes[i + 2]))};
                    refs += f.winding(w, tree.head);
                }
                for (size_t v = 0; v < modelVerts; ++v) refs += f.point(moved(v), tree.head);
            }
            return refs;
        }
        case SurfaceKind::Flare:
            return f.point(DVec3(ds.flareOrigin), tree.head);
        case SurfaceKind::Foghull:
            return f.everyLeaf(tree.head);
        default:
            return 0;
    }
}

}  // namespace q3::bspstage
