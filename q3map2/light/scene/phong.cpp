// Phong shading (smoothed vertex normals): the breaking angle of every surface and vertex, the
// spatially hashed grouping of coincident vertices, and the pipeline step that stores the result.
#include "phong.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <unordered_map>

#include "entity_keys.h"
#include "light_context.h"
#include "light_text.h"

namespace q3::light {
namespace {

// Hash cells are far larger than the position epsilon, so coincident vertices are always in the
// same or a neighbouring cell.
constexpr float kCellSize = 1.0f;
constexpr double kCellLimit = 1 << 20;  // beyond any map: clamps wild (or NaN) coordinates

struct Cell {
    int32_t x = 0, y = 0, z = 0;
    bool operator==(const Cell&) const = default;
};

struct CellHash {
    size_t operator()(const Cell& c) const {
        uint64_t h = static_cast<uint32_t>(c.x);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(c.y);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(c.z);
        return static_cast<size_t>(h ^ (h >> 29));
    }
};

int32_t cellCoordinate(float v) {
    double c = std::floor(static_cast<double>(v) / kCellSize);
    if (!(c >= -kCellLimit)) c = -kCellLimit;  // also catches NaN
    if (c > kCellLimit) c = kCellLimit;
    return static_cast<int32_t>(c);
}

Cell cellOf(Vec3 p) { return {cellCoordinate(p.x), cellCoordinate(p.y), cellCoordinate(p.z)}; }

bool samePosition(Vec3 a, Vec3 b) {
    return std::fabs(a.x - b.x) < kShadePositionEpsilon && std::fabs(a.y - b.y) < kShadePositionEpsilon &&
           std::fabs(a.z - b.z) < kShadePositionEpsilon;
}

bool sameNormal(Vec3 a, Vec3 b) {
    return std::fabs(a.x - b.x) < kShadeNormalEpsilon && std::fabs(a.y - b.y) < kShadeNormalEpsilon &&
           std::fabs(a.z - b.z) < kShadeNormalEpsilon;
}

// Angle between two stored normals, in double precision as q3map2 measures it.
double angleBetween(Vec3 a, Vec3 b) {
    const double d = static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y + static_cast<double>(a.z) * b.z;
    return std::acos(std::clamp(d, -1.0, 1.0));
}

// Vertices (with a non-zero angle) grouped by hash cell: indices of each cell in ascending order.
struct VertexCells {
    std::unordered_map<Cell, std::vector<uint32_t>, CellHash> cells;
};

VertexCells bucketVertices(std::span<const Vec3> positions, std::span<const float> angles) {
    VertexCells grid;
    for (size_t i = 0; i < positions.size(); ++i)
        if (angles[i] > 0) grid.cells[cellOf(positions[i])].push_back(static_cast<uint32_t>(i));
    return grid;
}

// Indices >= `first` of the vertices in the 27 cells around `p`, ascending.
void candidatesNear(const VertexCells& grid, Vec3 p, uint32_t first, std::vector<uint32_t>& out) {
    out.clear();
    const Cell c = cellOf(p);
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                auto it = grid.cells.find(Cell{c.x + dx, c.y + dy, c.z + dz});
                if (it == grid.cells.end()) continue;
                const std::vector<uint32_t>& list = it->second;
                out.insert(out.end(), std::lower_bound(list.begin(), list.end(), first), list.end());
            }
    std::sort(out.begin(), out.end());
}

}  // namespace

float entityShadeAngle(const bsp::Entity& entity) {
    const std::optional<float> angle = floatKey(entity, {"_shadeangle", "_smoothnormals", "_sn", "_sa", "_smooth"});
    return angle && *angle > 0 ? *angle : 0.0f;
}

std::vector<float> modelShadeAngles(std::span<const bsp::Entity> entities, size_t modelCount) {
    std::vector<float> angles(modelCount, 0.0f);
    if (modelCount == 0) return angles;
    if (!entities.empty()) angles[0] = entityShadeAngle(entities.front());
    for (size_t e = 1; e < entities.size(); ++e) {
        const std::string* model = entities[e].find("model");
        if (!model || model->size() < 2 || (*model)[0] != '*') continue;
        const int index = std::atoi(model->c_str() + 1);
        if (index <= 0 || static_cast<size_t>(index) >= modelCount) continue;
        angles[static_cast<size_t>(index)] = entityShadeAngle(entities[e]);
    }
    return angles;
}

std::vector<float> surfaceShadeAngles(const bsp::Bsp& bsp, std::span<const float> shaderAngles,
                                      std::span<const float> modelAngles, float defaultAngle) {
    // Entity angle of each surface: the world's unless a model claims it.
    const float worldAngle = modelAngles.empty() ? 0.0f : modelAngles[0];
    std::vector<float> entityAngles(bsp.surfaces.size(), worldAngle);
    for (size_t m = 0; m < bsp.models.size() && m < modelAngles.size(); ++m) {
        const bsp::Model& model = bsp.models[m];
        for (int i = 0; i < model.numSurfaces; ++i) {
            const int64_t s = static_cast<int64_t>(model.firstSurface) + i;
            if (s >= 0 && static_cast<size_t>(s) < entityAngles.size()) entityAngles[static_cast<size_t>(s)] = modelAngles[m];
        }
    }
    std::vector<float> angles(bsp.surfaces.size(), 0.0f);
    for (size_t s = 0; s < angles.size(); ++s) {
        const float shader = s < shaderAngles.size() ? shaderAngles[s] : 0.0f;
        if (shader > 0)
            angles[s] = shader;
        else if (entityAngles[s] > 0)
            angles[s] = entityAngles[s];
        else
            angles[s] = std::max(defaultAngle, 0.0f);
    }
    return angles;
}

std::vector<float> vertexShadeAngles(const bsp::Bsp& bsp, std::span<const float> surfaceAngles) {
    std::vector<float> angles(bsp.drawVerts.size(), 0.0f);
    for (size_t s = 0; s < bsp.surfaces.size(); ++s) {
        const bsp::Surface& surface = bsp.surfaces[s];
        const float angle = surface.surfaceType == bsp::MST_TRIANGLE_SOUP || s >= surfaceAngles.size()
                                ? 0.0f
                                : surfaceAngles[s];
        for (int v = 0; v < surface.numVerts; ++v) {
            const int64_t index = static_cast<int64_t>(surface.firstVert) + v;
            if (index >= 0 && static_cast<size_t>(index) < angles.size()) angles[static_cast<size_t>(index)] = angle;
        }
    }
    return angles;
}

SmoothedNormals smoothVertexNormals(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                    std::span<const float> angleDegrees) {
    SmoothedNormals result;
    result.normals.assign(normals.begin(), normals.end());
    const size_t count = std::min({positions.size(), normals.size(), angleDegrees.size()});
    std::vector<float> radians(count);
    for (size_t i = 0; i < count; ++i) radians[i] = angleDegrees[i] > 0 ? degToRad(angleDegrees[i]) : 0.0f;
    if (std::none_of(radians.begin(), radians.end(), [](float a) { return a > 0; })) return result;

    const VertexCells grid = bucketVertices(positions.first(count), radians);
    std::vector<uint8_t> grouped(count, 0);
    std::vector<uint32_t> candidates, members;
    std::vector<Vec3> votes;
    for (size_t i = 0; i < count; ++i) {
        if (grouped[i] || radians[i] <= 0) continue;
        candidatesNear(grid, positions[i], static_cast<uint32_t>(i), candidates);
        members.clear();
        votes.clear();
        Vec3 sum{};
        for (uint32_t j : candidates) {
            if (members.size() >= static_cast<size_t>(kShadeMaxGroup)) break;
            if (grouped[j] || !samePosition(positions[i], positions[j])) continue;
            const float breaking = std::min(radians[i], radians[j]);
            if (angleBetween(normals[i], normals[j]) + kShadeThetaEpsilon >= breaking) continue;
            members.push_back(j);
            grouped[j] = 1;
            const bool voted = std::any_of(votes.begin(), votes.end(), [&](Vec3 v) { return sameNormal(normals[j], v); });
            if (!voted) {
                votes.push_back(normals[j]);
                sum += normals[j];
            }
        }
        if (members.size() < 2) continue;
        const Vec3 average = normalize(sum);
        if (average == Vec3{}) continue;
        for (uint32_t j : members) result.normals[j] = average;
        result.smoothedVertexes += members.size();
    }
    return result;
}

void smoothNormals(LightContext& ctx, Log& log) {
    ctx.shadedNormals.clear();
    if (!ctx.options.shade) return;
    const bsp::Bsp& bsp = ctx.bsp;

    // Each surface's shader angle: the compile-time shader the .srf names, else the BSP shader.
    std::vector<float> bspShaderAngles(bsp.shaders.size(), 0.0f);
    if (ctx.shaderTable)
        for (size_t i = 0; i < bsp.shaders.size(); ++i) {
            const char* name = bsp.shaders[i].name;
            bspShaderAngles[i] = ctx.shaderTable->find(std::string(name, strnlen(name, sizeof(bsp.shaders[i].name))))
                                     .shadeAngleDegrees;
        }
    std::vector<float> shaderAngles(bsp.surfaces.size(), 0.0f);
    for (size_t s = 0; s < bsp.surfaces.size(); ++s) {
        const int shaderNum = bsp.surfaces[s].shaderNum;
        if (ctx.extras.loaded && ctx.shaderTable) {
            const std::string& srfShader = ctx.extras.forSurface(static_cast<int>(s)).shader;
            if (!srfShader.empty()) {
                shaderAngles[s] = ctx.shaderTable->find(srfShader).shadeAngleDegrees;
                continue;
            }
        }
        if (shaderNum >= 0 && static_cast<size_t>(shaderNum) < bspShaderAngles.size())
            shaderAngles[s] = bspShaderAngles[static_cast<size_t>(shaderNum)];
    }
    const std::vector<float> surfaceAngles = surfaceShadeAngles(
        bsp, shaderAngles, modelShadeAngles(ctx.entities, bsp.models.size()), ctx.options.shadeAngle);
    const std::vector<float> vertexAngles = vertexShadeAngles(bsp, surfaceAngles);

    // World positions (brush model origins applied) and stored normals of every draw vertex.
    std::vector<Vec3> positions(bsp.drawVerts.size()), normals(bsp.drawVerts.size());
    for (size_t v = 0; v < bsp.drawVerts.size(); ++v) {
        positions[v] = Vec3::fromArray(bsp.drawVerts[v].xyz);
        normals[v] = Vec3::fromArray(bsp.drawVerts[v].normal);
    }
    for (size_t s = 0; s < bsp.surfaces.size() && s < ctx.surfaceOffsets.size(); ++s) {
        const bsp::Surface& surface = bsp.surfaces[s];
        for (int v = 0; v < surface.numVerts; ++v) {
            const int64_t index = static_cast<int64_t>(surface.firstVert) + v;
            if (index >= 0 && static_cast<size_t>(index) < positions.size())
                positions[static_cast<size_t>(index)] = Vec3::fromArray(bsp.drawVerts[static_cast<size_t>(index)].xyz) +
                                                        ctx.surfaceOffsets[s];
        }
    }

    SmoothedNormals smoothed = smoothVertexNormals(positions, normals, vertexAngles);
    log.info(strCat("phong shading: ", smoothed.smoothedVertexes, " of ", bsp.drawVerts.size(),
                    " vertexes smoothed"));
    if (smoothed.smoothedVertexes > 0) ctx.shadedNormals = std::move(smoothed.normals);
}

}  // namespace q3::light
