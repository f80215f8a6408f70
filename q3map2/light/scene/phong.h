// Phong shading: the normal every draw vertex is lit with when coincident vertices of smooth
// surfaces share an averaged normal (q3map2's SmoothNormals, run by -shade / -shadeangle).
//
// Rules, as q3map2's light stage applies them (SmoothNormals in light_ydnar):
// - each surface has a breaking angle: its shader's q3map_shadeAngle when > 0, else its entity's
//   _shadeangle (aliases _smoothnormals, _sn, _sa, _smooth) when > 0, else the -shadeangle default
//   (0 with a bare -shade, so that only shaders and entities that ask are smoothed). q3map2 reads
//   the entity key only in -bsp (SmoothMetaTriangles, same order: shader, entity, default); here
//   the BSP's worldspawn and brush-model entities carry it into the light stage;
// - triangle soups are left alone (-bsp already smoothed their normals);
// - vertices within 0.001 units of each other (world space, brush model origins applied, so
//   surfaces of different entities meet) whose original normals lie less than the smaller of
//   their two angles apart are grouped, in vertex order, at most 256 to a group;
// - a group of two or more gets the normalised sum of its distinct normals (normals within 0.01
//   per component count once); every other vertex keeps its own normal.
// The BSP's stored normals never change: the result only feeds lighting.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "bspfile.h"
#include "vec3.h"

namespace q3::light {

constexpr float kShadePositionEpsilon = 0.001f;  // EQUAL_EPSILON of q3map2's VectorCompare
constexpr float kShadeNormalEpsilon = 0.01f;     // EQUAL_NORMAL_EPSILON: normals voting once
constexpr double kShadeThetaEpsilon = 0.000001;  // THETA_EPSILON: angles this close do not smooth
constexpr int kShadeMaxGroup = 256;              // MAX_SAMPLES: vertices in one group

// The per-entity breaking angle in degrees: the first of _shadeangle, _smoothnormals, _sn, _sa,
// _smooth that is present (atof semantics), negative values read as 0; 0 when none is set.
float entityShadeAngle(const bsp::Entity& entity);

// Breaking angle (degrees) of each BSP model from the entity that owns it: worldspawn for model 0,
// the entity whose "model" key is "*N" for model N; 0 for models no entity names.
std::vector<float> modelShadeAngles(std::span<const bsp::Entity> entities, size_t modelCount);

// Breaking angle (degrees) of each BSP surface. `shaderAngles` holds each surface's shader angle
// (q3map_shadeAngle, 0 = unset), `modelAngles` each model's entity angle; surfaces outside every
// model use the world's. The shader wins, then the entity, then `defaultAngle`.
std::vector<float> surfaceShadeAngles(const bsp::Bsp& bsp, std::span<const float> shaderAngles,
                                      std::span<const float> modelAngles, float defaultAngle);

// Breaking angle (degrees) of each draw vertex: its surface's, 0 for triangle soups and for
// vertices no surface references. When surfaces overlap the later one wins.
std::vector<float> vertexShadeAngles(const bsp::Bsp& bsp, std::span<const float> surfaceAngles);

struct SmoothedNormals {
    std::vector<Vec3> normals;        // one per vertex
    size_t smoothedVertexes = 0;      // vertices that took a group's averaged normal
};

// The smoothing itself, on plain arrays of equal length (one entry per vertex): world positions,
// original normals and breaking angles in degrees (0 = never smoothed). Positions are bucketed
// in a spatial hash, so the cost is linear in the vertex count; the result depends only on the
// input order.
SmoothedNormals smoothVertexNormals(std::span<const Vec3> positions, std::span<const Vec3> normals,
                                    std::span<const float> angleDegrees);

}  // namespace q3::light
