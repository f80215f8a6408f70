#include "bsp_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "patch.h"
#include "patch_drawvert.h"

namespace q3::bspstage::test {
namespace {

bool insideBrush(const bsp::Bsp& bsp, const bsp::Brush& brush, const Vec3& p) {
    for (int s = 0; s < brush.numSides; ++s) {
        const bsp::Plane& plane = bsp.planes[size_t(bsp.brushSides[size_t(brush.firstSide + s)].planeNum)];
        if (dot(Vec3::fromArray(plane.normal), p) - plane.dist > 0) return false;
    }
    return true;
}

double planeDifference(const bsp::Plane& a, const bsp::Plane& b) {
    double d = std::fabs(double(a.dist) - double(b.dist));
    for (int k = 0; k < 3; ++k) d = std::max(d, std::fabs(double(a.normal[k]) - double(b.normal[k])));
    return d;
}

std::vector<const bsp::Plane*> sidePlanes(const bsp::Bsp& bsp, const bsp::Brush& brush) {
    std::vector<const bsp::Plane*> out;
    for (int s = 0; s < brush.numSides; ++s)
        out.push_back(&bsp.planes[size_t(bsp.brushSides[size_t(brush.firstSide + s)].planeNum)]);
    return out;
}

// The largest distance from a plane of `from` to its nearest plane in `to`.
double farthestNearest(const std::vector<const bsp::Plane*>& from, const std::vector<const bsp::Plane*>& to) {
    double worst = 0;
    for (const bsp::Plane* p : from) {
        double nearest = 1e30;
        for (const bsp::Plane* q : to) nearest = std::min(nearest, planeDifference(*p, *q));
        worst = std::max(worst, nearest);
    }
    return worst;
}

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * double(length(cross(b - a, c - a))); }

}  // namespace

int pointContents(const bsp::Bsp& bsp, const Vec3& point) {
    int node = 0;
    while (node >= 0) {
        const bsp::Node& n = bsp.nodes[size_t(node)];
        const bsp::Plane& plane = bsp.planes[size_t(n.planeNum)];
        node = n.children[dot(Vec3::fromArray(plane.normal), point) - plane.dist >= 0 ? 0 : 1];
    }
    const bsp::Leaf& leaf = bsp.leafs[size_t(-node - 1)];
    int contents = 0;
    for (int i = 0; i < leaf.numLeafBrushes; ++i) {
        const bsp::Brush& brush = bsp.brushes[size_t(bsp.leafBrushes[size_t(leaf.firstLeafBrush + i)])];
        if (insideBrush(bsp, brush, point)) contents |= bsp.shaders[size_t(brush.shaderNum)].contentFlags;
    }
    return contents;
}

BrushPlaneComparison compareBrushPlanes(const bsp::Bsp& ours, const bsp::Bsp& theirs) {
    BrushPlaneComparison out;
    out.brushes = int(std::min(ours.brushes.size(), theirs.brushes.size()));
    for (size_t i = 0; i < size_t(out.brushes); ++i) {
        const bsp::Brush& a = ours.brushes[i];
        const bsp::Brush& b = theirs.brushes[i];
        if (std::string(ours.shaders[size_t(a.shaderNum)].name) != theirs.shaders[size_t(b.shaderNum)].name)
            ++out.otherShader;
        if (a.numSides != b.numSides) ++out.otherSideCount;
        const auto pa = sidePlanes(ours, a), pb = sidePlanes(theirs, b);
        out.worstPlane = std::max({out.worstPlane, farthestNearest(pa, pb), farthestNearest(pb, pa)});
    }
    return out;
}

std::vector<Vec3> randomPoints(const bsp::Bsp& bsp, int count, unsigned seed) {
    const bsp::Model& world = bsp.models.at(0);
    std::mt19937 random(seed);
    std::vector<Vec3> out;
    for (int i = 0; i < count; ++i) {
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
            std::uniform_real_distribution<float> along(world.mins[k], world.maxs[k]);
            p[k] = along(random);
        }
        out.push_back(p);
    }
    return out;
}

std::map<std::string, double> drawnAreaByShader(const bsp::Bsp& bsp) {
    std::map<std::string, double> area;
    for (const bsp::Surface& s : bsp.surfaces) {
        const std::string name = bsp.shaders.at(size_t(s.shaderNum)).name;
        double total = 0;
        if (s.surfaceType == bsp::MST_PATCH) {
            const std::span<const bsp::DrawVert> verts(&bsp.drawVerts[size_t(s.firstVert)], size_t(s.numVerts));
            patch::TessellationOptions options;
            options.iterations = 3;
            const patch::PatchMesh mesh = patch::tessellate(patch::gridFromDrawVerts(verts, s.patchWidth, s.patchHeight), options);
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
                total += triangleArea(mesh.verts[mesh.indices[i]].xyz, mesh.verts[mesh.indices[i + 1]].xyz,
                                      mesh.verts[mesh.indices[i + 2]].xyz);
        } else if (s.surfaceType == bsp::MST_PLANAR || s.surfaceType == bsp::MST_TRIANGLE_SOUP) {
            auto xyz = [&](int index) {
                return Vec3::fromArray(bsp.drawVerts[size_t(s.firstVert + bsp.drawIndexes[size_t(s.firstIndex + index)])].xyz);
            };
            for (int i = 0; i + 2 < s.numIndexes; i += 3) total += triangleArea(xyz(i), xyz(i + 1), xyz(i + 2));
        }
        area[name] += total;
    }
    return area;
}

AreaComparison compareAreas(const std::map<std::string, double>& ours, const std::map<std::string, double>& theirs,
                            double tolerance) {
    std::map<std::string, std::pair<double, double>> both;
    for (const auto& [name, a] : ours) both[name].first = a;
    for (const auto& [name, a] : theirs) both[name].second = a;
    AreaComparison out;
    for (const auto& [name, pair] : both) {
        if (pair.first == 0 && pair.second == 0) continue;
        ++out.shaders;
        const double larger = std::max(pair.first, pair.second);
        if (std::fabs(pair.first - pair.second) <= tolerance * larger) {
            ++out.within;
        } else {
            char text[256];
            std::snprintf(text, sizeof text, "%s: %.1f vs %.1f", name.c_str(), pair.first, pair.second);
            out.outside.push_back(text);
        }
    }
    return out;
}

}  // namespace q3::bspstage::test
