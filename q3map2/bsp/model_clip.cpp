#include "model_clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "clip_sides.h"
#include "clip_windings.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

using namespace clipflag;

constexpr int kShapeFlags = All & ~Model;

bool isMergedShape(int shape) {
    switch (shape) {
        case Pyramidal:
        case Pyramidal | AxialBackplane:
        case FaceNormals:
        case FaceNormals | Pyramidal:
        case Terrain:
        case Downwards:
        case Upwards:
        case Downwards | Upwards:
            return true;
        default:
            return false;
    }
}

bool isVolumetricShape(int shape) {
    switch (shape) {
        case AxialBackplane:
        case AxialBackplane | Terrain:
        case AxialBackplane | Downwards:
        case AxialBackplane | Upwards:
        case AxialBackplane | Downwards | Upwards:
        case MaxExtrude | Terrain:
        case MaxExtrude | Downwards:
        case MaxExtrude | Upwards:
        case MaxExtrude | Downwards | Upwards:
            return true;
        default:
            return false;
    }
}

std::string describe(const std::vector<DVec3>& p, const std::string& modelName) {
    char text[200];
    std::snprintf(text, sizeof text, "(%6.0f %6.0f %6.0f) (%6.0f %6.0f %6.0f) (%6.0f %6.0f %6.0f)", p[0].x, p[0].y,
                  p[0].z, p[1].x, p[1].y, p[1].z, p[2].x, p[2].y, p[2].z);
    return std::string("triangle ") + text + " of " + modelName + " was not autoclipped";
}

class BrushMaker {
public:
    BrushMaker(const ClipRequest& request, const ClipOptions& options, PlaneSet& planes, ClipBrushes& out)
        : request_(request), options_(options), planes_(planes), out_(out) {}

    // The brush of `cs`; a merged volume (`fronts`) has one front side per face in place of cs.front.
    void make(const ClipSides& cs, const ShaderInfo& shader, const std::vector<ClipFace>* fronts = nullptr) {
        Brush b;
        b.mapEntityNum = request_.mapEntityNum;
        b.contentShader = &shader;
        b.compileFlags = shader.compileFlags;
        b.contentFlags = shader.contentFlags;
        b.detail = true;
        if (fronts)
            for (const ClipFace& f : *fronts) b.sides.push_back(side(floatPlane(f.plane), f.points));
        else
            b.sides.push_back(side(cs.front, cs.points));
        const size_t frontCount = b.sides.size();
        for (size_t i = 0; i < cs.sides.size(); ++i) b.sides.push_back(side(floatPlane(cs.sides[i]), {cs.points[i], cs.next(i)}));
        if (cs.hasBack) b.sides.push_back(side(cs.back, cs.backPoints));
        const bool debug = request_.debugShaders[0] != nullptr;
        for (size_t s = 0; s < b.sides.size(); ++s) {
            const bool front = s < frontCount;
            b.sides[s].shader = debug ? request_.debugShaders[front ? 0 : 1] : (front ? &shader : nullptr);
            b.sides[s].surfaceFlags = front && !debug ? shader.surfaceFlags : 0;
        }
        if (!createBrushWindings(b, planes_)) return warn(cs.points);
        addBrushBevels(b, planes_, options_.bevelSnap);
        out_.brushes.push_back(std::move(b));
    }

    void warn(const std::vector<DVec3>& points) { out_.warnings.push_back(describe(points, *request_.modelName)); }

private:
    static DPlane floatPlane(const DPlane& p) { return {roundToFloat(p.normal), double(float(p.dist))}; }

    BrushSide side(const DPlane& plane, std::vector<DVec3> points) {
        BrushSide s;
        s.planeNum = planes_.find(plane, points);
        return s;
    }

    const ClipRequest& request_;
    const ClipOptions& options_;
    PlaneSet& planes_;
    ClipBrushes& out_;
};

bool clipsSolid(const ShaderInfo& shader) { return shader.clipModel || (shader.compileFlags & compileflags::Solid); }

DVec3 cornerOf(const DrawSurface& ds, size_t index) { return DVec3(xyzOf(ds.verts[size_t(ds.indexes[index])])); }
DVec3 exactCornerOf(const ClipSurface& s, size_t index) { return s.positions[size_t(s.ds->indexes[index])]; }

using TriangleSets = std::map<std::tuple<int, int, int>, std::vector<ClipWinding>>;

// Triangles of surfaces with equal surface, content and compile flags may merge.
TriangleSets triangleSets(std::span<const ClipSurface* const> surfaces) {
    TriangleSets sets;
    for (size_t s = 0; s < surfaces.size(); ++s) {
        const ClipSurface& cs = *surfaces[s];
        const ShaderInfo& si = *cs.ds->shader;
        auto& set = sets[{int(si.surfaceFlags), int(si.contentFlags), int(si.compileFlags)}];
        for (size_t i = 0; i + 2 < cs.ds->indexes.size(); i += 3) {
            ClipWinding w;
            if (clipTriangleWinding(exactCornerOf(cs, i), exactCornerOf(cs, i + 1), exactCornerOf(cs, i + 2), int(s), w))
                set.push_back(std::move(w));
        }
    }
    return sets;
}

// Per surface: the main axis of its triangles (their summed normals made axial; up when they
// cancel) and the float bounds of their corners.
struct SurfaceExtents {
    std::vector<DVec3> axes;
    std::vector<DBounds> bounds;
};

SurfaceExtents surfaceExtents(const TriangleSets& sets, size_t count) {
    SurfaceExtents out{std::vector<DVec3>(count, DVec3{0, 0, 0}), std::vector<DBounds>(count)};
    for (const auto& [key, set] : sets)
        for (const ClipWinding& w : set) {
            out.axes[size_t(w.surface)] += roundToFloat(w.plane.normal);
            for (const DVec3& p : w.points) out.bounds[size_t(w.surface)].add(roundToFloat(p));
        }
    for (DVec3& a : out.axes) a = a == DVec3{0, 0, 0} ? DVec3{0, 0, 1} : axialOf(roundToFloat(a));
    return out;
}

// The direction the extruding shapes push a polygon with this normal.
DVec3 extrusionFor(int shape, const DVec3& normal, const DVec3& mainAxis) {
    if (shape & Terrain) return mainAxis;
    if ((shape & Downwards) && (shape & Upwards)) return normal.z > 0 ? DVec3{0, 0, 1} : DVec3{0, 0, -1};
    if (shape & Downwards) return {0, 0, 1};
    if (shape & Upwards) return {0, 0, -1};
    return axialOf(normal);
}

struct ClipContext {
    int shape = 0;
    bool defaultShape = false;
    float clipDepth = 2, limitDepth = 0;
    PlaneEpsilons epsilons;
};

ClipSides sidesFor(std::vector<DVec3> points, const ClipContext& c) {
    ClipSides cs;
    cs.clipDepth = c.clipDepth;
    cs.points = std::move(points);
    return cs;
}

void clipMerged(std::span<const ClipSurface* const> surfaces, const ClipContext& c, BrushMaker& maker) {
    TriangleSets sets = triangleSets(surfaces);
    const SurfaceExtents extents = surfaceExtents(sets, surfaces.size());
    const int shape = c.shape;
    for (auto& [key, set] : sets)
        for (ClipWinding& w : mergeCoplanarWindings(std::move(set))) {
            ClipSides cs = sidesFor(std::move(w.points), c);
            if (!cs.construct(c.epsilons)) {
                maker.warn(cs.points);
                continue;
            }
            if (c.defaultShape) cs.defaultShape();
            else if (shape == Pyramidal) cs.pyramid();
            else if (shape == (Pyramidal | AxialBackplane)) cs.axialPyramid(c.limitDepth);
            else if (shape == FaceNormals) cs.faceNormals();
            else if (shape == (FaceNormals | Pyramidal)) cs.leaning45();
            else cs.extruded(extrusionFor(shape, cs.front.normal, extents.axes[size_t(w.surface)]));
            maker.make(cs, *surfaces[size_t(w.surface)]->ds->shader);
        }
}

// Backplane modes: coplanar polygons first, then polygons extruded the same way merged into convex
// volumes; a polygon that cannot be extruded that way gets the default shape.
void clipVolumes(std::span<const ClipSurface* const> surfaces, const ClipContext& c, BrushMaker& maker) {
    TriangleSets sets = triangleSets(surfaces);
    const SurfaceExtents extents = surfaceExtents(sets, surfaces.size());
    for (auto& [key, set] : sets) {
        std::vector<ClipWinding> extrudable;
        for (ClipWinding& w : mergeCoplanarWindings(std::move(set))) {
            w.extrusion = extrusionFor(c.shape, w.plane.normal, extents.axes[size_t(w.surface)]);
            if (dot(w.plane.normal, w.extrusion) >= 0.05) {
                w.fronts.push_back({w.plane, w.points, w.surface});
                extrudable.push_back(std::move(w));
                continue;
            }
            ClipSides cs = sidesFor(std::move(w.points), c);
            if (!cs.construct(c.epsilons)) {
                maker.warn(cs.points);
                continue;
            }
            cs.defaultShape();
            maker.make(cs, *surfaces[size_t(w.surface)]->ds->shader);
        }
        for (ClipWinding& w : mergeConvexVolumes(std::move(extrudable))) {
            DBounds bounds;
            for (const ClipFace& f : w.fronts) bounds.add(extents.bounds[size_t(f.surface)]);
            ClipSides cs = sidesFor(std::move(w.points), c);
            if (w.planar()) {
                if (!cs.construct(c.epsilons)) {
                    maker.warn(cs.points);
                    continue;
                }
            } else {
                cs.constructVolume(w.fronts[0].plane);
            }
            cs.specialBack(c.shape, w.extrusion, bounds, c.limitDepth);
            maker.make(cs, *surfaces[size_t(w.surface)]->ds->shader, w.planar() ? nullptr : &w.fronts);
        }
    }
}

void clipPerTriangle(std::span<const ClipSurface* const> surfaces, const ClipContext& c, BrushMaker& maker) {
    for (const ClipSurface* surface : surfaces) {
        const DrawSurface* ds = surface->ds;
        for (size_t i = 0; i + 2 < ds->indexes.size(); i += 3) {
            ClipSides cs = sidesFor({}, c);
            std::array<Vec3, 3> normals;
            for (size_t k = 0; k < 3; ++k) {
                cs.points.push_back(cornerOf(*ds, i + k));
                normals[k] = Vec3::fromArray(ds->verts[size_t(ds->indexes[i + k])].normal);
            }
            if (!cs.construct(c.epsilons)) {
                maker.warn(cs.points);
                continue;
            }
            cs.vertexNormals(normals, c.shape & Pyramidal);
            maker.make(cs, *ds->shader);
        }
    }
}

}  // namespace

ClipMode clipModeFor(int spawnFlags, const ShaderInfo& shader) {
    const int shape = spawnFlags & kShapeFlags;
    if ((shader.clipModel && shape == 0) || (spawnFlags & All) == Model) return ClipMode::Merged;
    if (isMergedShape(shape)) return ClipMode::Merged;
    if (shape == VertexNormals || shape == (VertexNormals | Pyramidal)) return ClipMode::PerTriangle;
    if (isVolumetricShape(shape)) return ClipMode::Volumetric;
    return (spawnFlags & All) ? ClipMode::Unknown : ClipMode::None;
}

ClipBrushes clipBrushesForModel(std::span<const ClipSurface> surfaces, const ClipRequest& request,
                                const ClipOptions& options, PlaneSet& planes) {
    ClipBrushes out;
    std::vector<const ClipSurface*> solid;
    ClipMode mode = ClipMode::None;
    for (const ClipSurface& s : surfaces) {
        const ClipMode m = clipModeFor(request.spawnFlags, *s.ds->shader);
        if (m == ClipMode::None || m == ClipMode::Unknown || !clipsSolid(*s.ds->shader)) continue;
        mode = m;
        solid.push_back(&s);
    }
    if (solid.empty()) return out;
    ClipContext c;
    c.shape = request.spawnFlags & kShapeFlags;
    c.defaultShape = c.shape == 0 || (request.spawnFlags & All) == Model;
    c.clipDepth = request.clipDepth;
    if (c.clipDepth < 0) {  // a negative depth: 2, and its size limits the backplane shapes
        c.limitDepth = -c.clipDepth;
        c.clipDepth = 2;
    }
    c.epsilons = planes.epsilons();
    BrushMaker maker(request, options, planes, out);
    if (mode == ClipMode::Merged) clipMerged(solid, c, maker);
    else if (mode == ClipMode::Volumetric) clipVolumes(solid, c, maker);
    else clipPerTriangle(solid, c, maker);
    return out;
}

void prependClipBrushes(BspEntity& e, std::vector<Brush> clip, std::vector<DrawSurface>& surfaces, Tree& tree) {
    if (clip.empty()) return;
    const int count = int(clip.size());
    std::reverse(clip.begin(), clip.end());
    e.brushes.insert(e.brushes.begin(), std::make_move_iterator(clip.begin()), std::make_move_iterator(clip.end()));
    for (DrawSurface& ds : surfaces)
        if (ds.brush >= 0) ds.brush += count;
    for (TreeNode& n : tree.nodes)
        for (int& b : n.brushes) b += count;
}

}  // namespace q3::bspstage
