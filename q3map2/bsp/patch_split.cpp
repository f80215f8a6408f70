#include "patch_split.h"

#include <cmath>

#include "vec3.h"
#include "winding.h"

namespace q3::bspstage {

PatchGrid transposeGrid(const PatchGrid& in) {
    PatchGrid out;
    out.width = in.height;
    out.height = in.width;
    out.verts.resize(in.verts.size());
    for (int h = 0; h < in.height; ++h)
        for (int w = 0; w < in.width; ++w) out.verts[size_t(w) * size_t(in.height) + size_t(h)] = in.at(w, h);
    return out;
}

void invertGrid(PatchGrid& grid) {
    for (int h = 0; h < grid.height; ++h)
        std::reverse(grid.verts.begin() + h * grid.width, grid.verts.begin() + (h + 1) * grid.width);
}

bsp::DrawVert lerpDrawVert(const bsp::DrawVert& a, const bsp::DrawVert& b, float amount) {
    bsp::DrawVert out{};
    for (int i = 0; i < 3; ++i) out.xyz[i] = a.xyz[i] + (b.xyz[i] - a.xyz[i]) * amount;
    for (int i = 0; i < 2; ++i) {
        out.st[i] = a.st[i] + (b.st[i] - a.st[i]) * amount;
        out.lightmap[i] = a.lightmap[i] + (b.lightmap[i] - a.lightmap[i]) * amount;
    }
    for (int i = 0; i < 4; ++i) out.color[i] = uint8_t(float(a.color[i]) + amount * float(int(b.color[i]) - int(a.color[i])));
    Vec3 n = Vec3::fromArray(a.normal) + (Vec3::fromArray(b.normal) - Vec3::fromArray(a.normal)) * amount;
    const float len = length(n);
    (len == 0 ? Vec3::fromArray(a.normal) : n * (1.0f / len)).toArray(out.normal);
    return out;
}

GridSplit splitGridByPlane(PatchGrid grid, const DPlane& plane) {
    std::vector<float> d;
    int split = -1;
    for (int attempt = 0; attempt < 2; ++attempt) {
        d.assign(grid.verts.size(), 0);
        int front = 0, back = 0;
        for (size_t i = 0; i < grid.verts.size(); ++i) {
            d[i] = float(plane.distanceTo(DVec3(Vec3::fromArray(grid.verts[i].xyz))));
            if (d[i] > kOnEpsilon) ++front;
            else if (d[i] < -kOnEpsilon) ++back;
        }
        if (!front) return {std::nullopt, std::move(grid)};
        if (!back) return {std::move(grid), std::nullopt};
        auto dist = [&](int w, int h) { return d[size_t(h) * size_t(grid.width) + size_t(w)]; };
        auto crosses = [&](int w, int h) { return (dist(w, h) < 0) != (dist(w + 1, h) < 0); };
        split = -1;
        for (int w = 0; w < grid.width - 1 && split < 0; ++w)
            if (crosses(w, 0)) split = w;
        if (split < 0) {
            if (attempt == 1) return {std::move(grid), std::nullopt};  // no crossing points
            grid = transposeGrid(grid);
            invertGrid(grid);
            continue;
        }
        for (int h = 1; h < grid.height; ++h) {
            for (int w = 0; w < grid.width - 1; ++w)
                if (crosses(w, h) && w != split) return {std::move(grid), std::nullopt};  // several crossings
            if (!crosses(split, h)) return {std::move(grid), std::nullopt};            // differing crossings
        }
        break;
    }

    auto dist = [&](int w, int h) { return d[size_t(h) * size_t(grid.width) + size_t(w)]; };
    PatchGrid f, b;
    f.width = split + 2;
    const bool frontPad = (f.width & 1) == 0;
    if (frontPad) ++f.width;
    b.width = grid.width - split;
    const bool backPad = (b.width & 1) == 0;
    if (backPad) ++b.width;
    f.height = b.height = grid.height;
    f.verts.resize(size_t(f.width) * size_t(f.height));
    b.verts.resize(size_t(b.width) * size_t(b.height));
    for (int w = 0; w < grid.width; ++w)
        for (int h = 0; h < grid.height; ++h) {
            if (w <= split)
                f.at(w, h) = grid.at(w, h);
            else
                b.at(w - split + (backPad ? 1 : 0), h) = grid.at(w, h);
        }
    for (int h = 0; h < grid.height; ++h) {
        const float frac = dist(split, h) / (dist(split, h) - dist(split + 1, h));
        const bsp::DrawVert cut = lerpDrawVert(grid.at(split, h), grid.at(split + 1, h), frac);
        f.at(split + 1, h) = cut;
        if (frontPad) f.at(split + 2, h) = cut;
        b.at(0, h) = cut;
        if (backPad) b.at(1, h) = cut;
    }
    const bool firstInFront = dist(0, 0) > 0;
    GridSplit out;
    out.front = firstInFront ? std::move(f) : std::move(b);
    out.back = firstInFront ? std::move(b) : std::move(f);
    return out;
}

}  // namespace q3::bspstage
