// Quake 3 MD3 models for misc_model: the surfaces of one frame, as q3map2 gets them through its
// model importer: each surface's first shader name, its vertices in the order its triangles first
// use them (texture coordinates as stored, normals decoded from their latitude/longitude bytes)
// and its triangles in the file's corner order.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vec3.h"

namespace q3::bspstage {

struct ModelVertex {
    Vec3 xyz;
    Vec3 normal;
    float st[2] = {0, 0};
};

struct ModelSurface {
    std::string name;
    std::string shader;
    std::vector<ModelVertex> verts;
    std::vector<int> indexes;  // triangles
};

// Parses an MD3 file image; `frame` past the last frame uses the last one. Throws
// std::runtime_error naming `fileName` and what is wrong.
std::vector<ModelSurface> parseMd3(std::span<const uint8_t> bytes, int frame, const std::string& fileName);

}  // namespace q3::bspstage
