// The C interface: thin wrappers that catch everything so no exception crosses into C.
#include "sh_grid_runtime_c.h"

#include <cstring>

#include "c_api_support.h"
#include "sh_grid_runtime.h"

struct q3sh_grid {
    q3::sh::GridRuntime runtime;
};

namespace {

q3::sh::GridPointSH fromFloats(const float coeffs[27]) {
    q3::sh::GridPointSH p;
    std::memcpy(p.coeffs, coeffs, sizeof p.coeffs);
    return p;
}

}  // namespace

extern "C" {

q3sh_grid* q3sh_grid_load(const unsigned char* bsp, size_t size, char* error, size_t errorSize) {
    return q3::sh::capi::loadHandle<q3sh_grid>(
        bsp, size, error, errorSize, "the light grid",
        [](q3sh_grid& h, const unsigned char* b, size_t n) { return h.runtime.loadFromBsp(b, n); });
}

void q3sh_grid_free(q3sh_grid* grid) { delete grid; }

int q3sh_grid_source(const q3sh_grid* grid) {
    if (grid == nullptr) return Q3SH_SOURCE_NONE;
    switch (grid->runtime.source()) {
        case q3::sh::GridSource::Lump18: return Q3SH_SOURCE_LUMP18;
        case q3::sh::GridSource::Bspx: return Q3SH_SOURCE_BSPX;
        case q3::sh::GridSource::Legacy: return Q3SH_SOURCE_LEGACY;
        case q3::sh::GridSource::None: break;
    }
    return Q3SH_SOURCE_NONE;
}

void q3sh_grid_info(const q3sh_grid* grid, float mins[3], float cellSize[3], int bounds[3]) {
    for (int axis = 0; axis < 3; ++axis) {
        const bool ok = grid != nullptr;
        if (mins) mins[axis] = ok ? grid->runtime.grid().mins[axis] : 0.0f;
        if (cellSize) cellSize[axis] = ok ? grid->runtime.grid().size[axis] : 0.0f;
        if (bounds) bounds[axis] = ok ? grid->runtime.grid().bounds[axis] : 0;
    }
}

void q3sh_grid_sample(const q3sh_grid* grid, const float position[3], float coeffs[27]) {
    if (coeffs == nullptr) return;
    q3::sh::GridPointSH p{};
    if (grid != nullptr && position != nullptr) p = grid->runtime.sample(position);
    std::memcpy(coeffs, p.coeffs, sizeof p.coeffs);
}

void q3sh_eval_irradiance(const float coeffs[27], const float normal[3], float rgb[3]) {
    if (rgb == nullptr) return;
    if (coeffs == nullptr || normal == nullptr) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    q3::sh::irradianceAt(fromFloats(coeffs), normal, rgb);
}

void q3sh_ambient_cube(const float coeffs[27], float faces[18]) {
    if (faces == nullptr) return;
    q3::sh::AmbientCube cube;
    if (coeffs != nullptr) cube = q3::sh::toAmbientCube(fromFloats(coeffs));
    std::memcpy(faces, cube.face, sizeof cube.face);
}

void q3sh_legacy_lighting(const float coeffs[27], float direction[3], float directed[3], float ambient[3]) {
    q3::sh::LegacyLighting light;
    if (coeffs != nullptr) light = q3::sh::toLegacyLighting(fromFloats(coeffs));
    for (int axis = 0; axis < 3; ++axis) {
        if (direction) direction[axis] = light.direction[axis];
        if (directed) directed[axis] = light.directed[axis];
        if (ambient) ambient[axis] = light.ambient[axis];
    }
}

}  // extern "C"
