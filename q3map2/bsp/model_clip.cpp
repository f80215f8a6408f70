#include "model_clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "float_plane.h"
#include "shader_info.h"

namespace q3::bspstage {
namespace {

using Triangle = std::array<Vec3, 3>;

bool planeFromPoints(FPlane& plane, const Triangle& p) { return floatPlaneFromPoints(plane, p[0], p[1], p[2]); }

Vec3 centre(const Triangle& p) {
    const Vec3 sum = p[0] + p[1] + p[2];
    return {float(double(sum.x) / 3.0), float(double(sum.y) / 3.0), float(double(sum.z) / 3.0)};
}

// Two normal components both tiny but not both zero: flatten the triangle along the third axis.
bool flattenNearAxial(FPlane& plane, Triangle& p) {
    for (int j = 0; j < 3; ++j) {
        const float a = plane.normal[j], b = plane.normal[(j + 1) % 3];
        if (std::fabs(a) < 0.00025 && std::fabs(b) < 0.00025 && (a != 0 || b != 0)) {
            const float c = centre(p)[(j + 2) % 3];
            for (Vec3& q : p) q[(j + 2) % 3] = c;
            return true;
        }
    }
    return false;
}

// The smallest angle's squared sine (q3map2 triangle_min_angle_squared_sin).
double minAngleSquaredSin(const Triangle& p) {
    const Vec3 d[3] = {p[1] - p[0], p[2] - p[0], p[2] - p[1]};
    const double l[3] = {dot(d[0], d[0]), dot(d[1], d[1]), dot(d[2], d[2])};
    const int mini = l[0] < l[1] ? (l[0] < l[2] ? 0 : 2) : (l[1] < l[2] ? 1 : 2);
    if (l[mini] == 0) return 0;
    const int minj = mini == 2 ? 0 : mini + 1, mink = minj == 2 ? 0 : minj + 1;
    const Vec3 c = cross(d[minj], d[mink]);
    return double(dot(c, c)) / (l[minj] * l[mink]);
}

int maxAbsComponent(const Vec3& v) {
    int best = 0;
    for (int i = 1; i < 3; ++i)
        if (std::fabs(v[i]) > std::fabs(v[best])) best = i;
    return best;
}

std::string describe(const Triangle& p) {
    char text[160];
    std::snprintf(text, sizeof text, "(%6.0f %6.0f %6.0f) (%6.0f %6.0f %6.0f) (%6.0f %6.0f %6.0f)", p[0].x, p[0].y,
                  p[0].z, p[1].x, p[1].y, p[1].z, p[2].x, p[2].y, p[2].z);
    return text;
}

// The triangle's plane and points after q3map2's snapping of nearly axial planes and edges; false
// when the triangle has no plane.
bool snappedPlane(FPlane& plane, Triangle& p) {
    if (!planeFromPoints(plane, p)) return false;
    bool snapped = flattenNearAxial(plane, p);
    for (int j = 0; j < 3; ++j) {
        Vec3& a = p[size_t(j)];
        Vec3& b = p[size_t((j + 1) % 3)];
        const Vec3 edge = normalizedLikeQ3map2(a - b);
        for (int k = 0; k < 3; ++k)
            if (edge[k] != 0 && std::fabs(edge[k]) < 0.00025) {
                a[k] = b[k] = float(double(a[k] + b[k]) / 2.0);
                snapped = true;
            }
    }
    if (snapped) planeFromPoints(plane, p);
    if (flattenNearAxial(plane, p)) planeFromPoints(plane, p);
    snapped = false;
    for (int j = 0; j < 3; ++j)
        if (plane.normal[j] != 0 && std::fabs(plane.normal[j]) < 0.00005) {
            plane.normal[j] = 0;
            snapped = true;
        }
    if (snapped) {
        const Vec3 c = centre(p);
        plane.normal = normalizedLikeQ3map2(plane.normal);
        plane.dist = dot(plane.normal, c);
        for (Vec3& q : p) q = q - plane.normal * (dot(plane.normal, q) - plane.dist);
    }
    return true;
}

BrushSide sideOn(PlaneSet& planes, const FPlane& plane, std::initializer_list<Vec3> points) {
    std::vector<DVec3> onPlane;
    for (const Vec3& q : points) onPlane.push_back(DVec3(q));
    BrushSide side;
    side.planeNum = planes.find({DVec3(plane.normal), double(plane.dist)}, onPlane);
    return side;
}

}  // namespace

bool wantsDefaultClip(int spawnFlags, const ShaderInfo& shader) {
    const int modes = spawnFlags & (kAutoclipFlags & ~kClipModelFlag);
    return (shader.clipModel && modes == 0) || (spawnFlags & kAutoclipFlags) == kClipModelFlag;
}

ClipBrushes clipBrushesForSurface(const DrawSurface& ds, const ShaderInfo& shader, int mapEntityNum, float clipDepth,
                                  const ClipOptions& options, const ShaderInfo* (*debugShaders)[2],
                                  const std::string& modelName, PlaneSet& planes) {
    ClipBrushes out;
    if (!shader.clipModel && !(shader.compileFlags & compileflags::Solid)) return out;
    if (clipDepth < 0) clipDepth = 2;  // q3map2 keeps the size for modes this build refuses
    const ShaderInfo* front = debugShaders ? (*debugShaders)[0] : &shader;
    const ShaderInfo* others = debugShaders ? (*debugShaders)[1] : nullptr;
    for (size_t i = 0; i + 2 < ds.indexes.size(); i += 3) {
        Triangle p;
        for (size_t j = 0; j < 3; ++j) p[j] = xyzOf(ds.verts[size_t(ds.indexes[i + j])]);
        FPlane plane;
        if (!snappedPlane(plane, p)) continue;
        if (minAngleSquaredSin(p) < 1e-8) {
            out.warnings.push_back("triangle " + describe(p) + " of " + modelName + " was not autoclipped: points on line");
            continue;
        }
        // Sides along the axis nearest the triangle's normal, a back plane clipDepth behind it.
        Vec3 axis{0, 0, 0};
        const int a = maxAbsComponent(plane.normal);
        axis[a] = plane.normal[a] >= 0 ? 1.0f : -1.0f;
        FPlane edges[3];
        for (int j = 0; j < 3; ++j) {
            edges[j].normal = normalizedLikeQ3map2(cross(axis, p[size_t((j + 1) % 3)] - p[size_t(j)]));
            edges[j].dist = dot(p[size_t(j)], edges[j].normal);
        }
        FPlane back{-plane.normal, -plane.dist};
        back.dist += dot(axis, plane.normal) * clipDepth;

        Brush b;
        b.mapEntityNum = mapEntityNum;
        b.contentShader = &shader;
        b.compileFlags = shader.compileFlags;
        b.contentFlags = shader.contentFlags;
        b.detail = true;
        b.sides.push_back(sideOn(planes, plane, {p[0], p[1], p[2]}));
        b.sides.push_back(sideOn(planes, edges[0], {p[0], p[1]}));
        b.sides.push_back(sideOn(planes, edges[1], {p[1], p[2]}));
        b.sides.push_back(sideOn(planes, edges[2], {p[2], p[0]}));
        b.sides.push_back(sideOn(planes, back, {}));
        b.sides[0].shader = front;
        b.sides[0].surfaceFlags = shader.surfaceFlags;
        for (size_t s = 1; s < b.sides.size(); ++s) b.sides[s].shader = others;
        if (!createBrushWindings(b, planes)) {
            out.warnings.push_back("triangle " + describe(p) + " of " + modelName + " was not autoclipped");
            continue;
        }
        addBrushBevels(b, planes, options.bevelSnap);
        out.brushes.push_back(std::move(b));
    }
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
