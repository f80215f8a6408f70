// Tessellation of a control grid into a vertex grid and triangles, q3map2-style: uniform steps per
// span, optional removal of straight rows/columns, alternating quad diagonals.
#include <algorithm>

#include "patch.h"
#include "patch_eval.h"

namespace q3::patch {
namespace {

// Largest level not above `requested` whose vertex count along an axis of `spans` spans stays below
// q3map2's expansion limit.
int levelForAxis(int spans, int requested) {
    int level = std::clamp(requested, 0, kMaxIterations);
    while (level > 0 && spans * segmentsPerSpan(level) + 1 >= kMaxExpandedAxis) --level;
    return level;
}

// Distance of p from the infinite line through a and b (from a when a and b coincide).
float distanceFromLine(Vec3 p, Vec3 a, Vec3 b) {
    const Vec3 dir = normalize(b - a);
    const Vec3 projected = a + dir * dot(p - a, dir);
    return length(p - projected);
}

// Vertices inside a sub-patch that collapses to a line or a point have no tangent plane (and
// control normals may be absent). They take the average normal of the nearest vertices along their
// row and column that have one, searching outwards one step at a time.
void fillMissingNormals(PatchMesh& mesh) {
    const std::vector<PatchVertex> source = mesh.verts;
    const auto has = [&](int column, int row) {
        return column >= 0 && row >= 0 && column < mesh.width && row < mesh.height &&
               source[size_t(row) * mesh.width + column].normal != Vec3{};
    };
    const int reach = std::max(mesh.width, mesh.height);
    for (int row = 0; row < mesh.height; ++row) {
        for (int column = 0; column < mesh.width; ++column) {
            if (has(column, row)) continue;
            for (int d = 1; d < reach; ++d) {
                Vec3 sum;
                const int offsets[4][2] = {{d, 0}, {-d, 0}, {0, d}, {0, -d}};
                for (const auto& o : offsets)
                    if (has(column + o[0], row + o[1])) sum += source[size_t(row + o[1]) * mesh.width + column + o[0]].normal;
                if (sum != Vec3{}) {
                    mesh.verts[size_t(row) * mesh.width + column].normal = normalize(sum);
                    break;
                }
            }
        }
    }
}

}  // namespace

PatchMesh tessellate(const ControlGrid& grid, const TessellationOptions& options) {
    requireValidGrid(grid);
    const int spansU = (grid.width - 1) / 2;
    const int spansV = (grid.height - 1) / 2;
    const int segU = segmentsPerSpan(levelForAxis(spansU, options.iterations));
    const int segV = segmentsPerSpan(levelForAxis(spansV, options.iterations));

    PatchMesh mesh;
    mesh.width = spansU * segU + 1;
    mesh.height = spansV * segV + 1;
    mesh.verts.reserve(size_t(mesh.width) * mesh.height);
    for (int row = 0; row < mesh.height; ++row) {
        // The last row belongs to the last span at t = 1 so that edges land exactly on controls.
        const int spanV = std::min(row / segV, spansV - 1);
        const double tv = double(row - spanV * segV) / segV;
        for (int column = 0; column < mesh.width; ++column) {
            const int spanU = std::min(column / segU, spansU - 1);
            const double tu = double(column - spanU * segU) / segU;
            mesh.verts.push_back(evaluateSpan(grid, spanU, tu, spanV, tv, options.normals));
        }
    }
    fillMissingNormals(mesh);
    if (options.removeLinearRowsColumns) removeLinearRowsColumns(mesh);
    else triangulateGrid(mesh);
    return mesh;
}

PatchMesh tessellateForLighting(const ControlGrid& grid, float curveLength, int subdivisions) {
    TessellationOptions options;
    options.iterations = iterationsForCurve(curveLength, subdivisions);
    // Lighting uses the normals stored on the BSP's control vertices, as q3map2 does.
    options.normals = NormalSource::Interpolated;
    options.removeLinearRowsColumns = true;
    return tessellate(grid, options);
}

PatchMesh tessellateForLighting(const ControlGrid& grid) {
    return tessellateForLighting(grid, longestCurve(grid), kDefaultSubdivisions);
}

void removeLinearRowsColumns(PatchMesh& mesh, float epsilon) {
    // Columns first, then rows; after a removal the same index is tested again against its new
    // neighbour, so long straight runs collapse to their end points.
    for (int column = 1; column + 1 < mesh.width; ++column) {
        float worst = 0;
        for (int row = 0; row < mesh.height; ++row)
            worst = std::max(worst, distanceFromLine(mesh.at(column, row).xyz, mesh.at(column - 1, row).xyz,
                                                     mesh.at(column + 1, row).xyz));
        if (worst >= epsilon) continue;
        std::vector<PatchVertex> kept;
        kept.reserve(size_t(mesh.width - 1) * mesh.height);
        for (int row = 0; row < mesh.height; ++row)
            for (int c = 0; c < mesh.width; ++c)
                if (c != column) kept.push_back(mesh.at(c, row));
        mesh.verts = std::move(kept);
        --mesh.width;
        --column;
    }
    for (int row = 1; row + 1 < mesh.height; ++row) {
        float worst = 0;
        for (int column = 0; column < mesh.width; ++column)
            worst = std::max(worst, distanceFromLine(mesh.at(column, row).xyz, mesh.at(column, row - 1).xyz,
                                                     mesh.at(column, row + 1).xyz));
        if (worst >= epsilon) continue;
        mesh.verts.erase(mesh.verts.begin() + ptrdiff_t(row) * mesh.width,
                         mesh.verts.begin() + ptrdiff_t(row + 1) * mesh.width);
        --mesh.height;
        --row;
    }
    triangulateGrid(mesh);
}

void triangulateGrid(PatchMesh& mesh) {
    mesh.indices.clear();
    if (mesh.width < 2 || mesh.height < 2) return;
    mesh.indices.reserve(size_t(mesh.width - 1) * (mesh.height - 1) * 6);
    const auto index = [&](int column, int row) { return uint32_t(row * mesh.width + column); };
    for (int row = 0; row + 1 < mesh.height; ++row) {
        for (int column = 0; column + 1 < mesh.width; ++column) {
            // Quad corners in order around the quad, the first repeated; the diagonal alternates
            // like a checkerboard so that curved strips do not all lean the same way.
            const uint32_t ring[5] = {index(column, row), index(column, row + 1), index(column + 1, row + 1),
                                      index(column + 1, row), index(column, row)};
            const int r = (column + row) & 1;
            mesh.indices.insert(mesh.indices.end(), {ring[r], ring[r + 1], ring[r + 2]});
            mesh.indices.insert(mesh.indices.end(), {ring[r], ring[r + 2], ring[r + 3]});
        }
    }
}

Bounds meshBounds(const PatchMesh& mesh) {
    Bounds b;
    for (const PatchVertex& v : mesh.verts) b.add(v.xyz);
    return b;
}

}  // namespace q3::patch
