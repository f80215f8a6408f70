#include "autosprite2.h"

#include <array>
#include <utility>

namespace q3::bspstage {

std::string fixAutosprite2(DrawSurface& ds) {
    if (ds.verts.size() != 4 || ds.indexes.size() != 6)
        return "autosprite2 surface: ds->numVerts != 4 or ds->numIndexes != 6: must be simple rectangle";
    const DVec3 a(xyzOf(ds.verts[size_t(ds.indexes[0])])), b(xyzOf(ds.verts[size_t(ds.indexes[1])])),
        c(xyzOf(ds.verts[size_t(ds.indexes[2])]));
    const DVec3 n = cross(c - a, b - a);
    if (length(n) == 0) return "autosprite2 surface: degenerate triangle";
    const Vec3 normal = (n / length(n)).toFloat();

    // The two shortest of the six vertex pairs, as the engine's deform finds them.
    constexpr int kPairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    float shortest[2] = {999999, 999999};
    int pair[2] = {0, 0};
    for (int j = 0; j < 6; ++j) {
        const Vec3 d = xyzOf(ds.verts[size_t(kPairs[j][0])]) - xyzOf(ds.verts[size_t(kPairs[j][1])]);
        const float l = dot(d, d);
        if (l < shortest[0]) {
            pair[1] = pair[0];
            shortest[1] = shortest[0];
            pair[0] = j;
            shortest[0] = l;
        } else if (l < shortest[1]) {
            pair[1] = j;
            shortest[1] = l;
        }
    }
    std::array<std::array<int, 2>, 2> edge{{{kPairs[pair[0]][0], kPairs[pair[0]][1]}, {kPairs[pair[1]][0], kPairs[pair[1]][1]}}};
    if (edge[0][0] == edge[1][0] || edge[0][0] == edge[1][1] || edge[0][1] == edge[1][0] || edge[0][1] == edge[1][1])
        return "autosprite2 surface: two shortest edges share a vertex";

    auto at = [&](int i) { return xyzOf(ds.verts[size_t(i)]); };
    const Vec3 major = (at(edge[1][0]) + at(edge[1][1])) * 0.5f - (at(edge[0][0]) + at(edge[0][1])) * 0.5f;
    const Vec3 minor = cross(major, -normal);
    if (dot(at(edge[0][1]) - at(edge[0][0]), minor) < 0) std::swap(edge[0][0], edge[0][1]);
    if (dot(at(edge[1][1]) - at(edge[1][0]), minor) > 0) std::swap(edge[1][0], edge[1][1]);
    const std::array<bsp::DrawVert, 4> ordered{ds.verts[size_t(edge[0][0])], ds.verts[size_t(edge[0][1])],
                                               ds.verts[size_t(edge[1][0])], ds.verts[size_t(edge[1][1])]};
    ds.verts.assign(ordered.begin(), ordered.end());
    ds.indexes = {3, 0, 2, 2, 0, 1};
    if (!ds.tjunctionVerts.empty()) ds.tjunctionVerts.assign(4, false);
    return {};
}

}  // namespace q3::bspstage
