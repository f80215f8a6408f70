// Engine-side SH light grid: finds the grid in a BSP image (lump 18 of v47, the BSPX lump
// "LIGHTGRID_SH", else the legacy lump 15), samples it trilinearly and turns a sample into what
// shaders need. No dependencies and no exceptions besides std::bad_alloc; see
// docs/sh-engine-integration.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sh_grid_lump.h"

namespace q3::sh {

enum class GridSource { None, Lump18, Bspx, Legacy };

// Irradiance towards +X, -X, +Y, -Y, +Z, -Z (clamped at 0).
struct AmbientCube {
    float face[6][3] = {};
};

// For shaders written for the legacy grid: light = ambient + directed * max(0, n.direction).
struct LegacyLighting {
    float direction[3] = {0, 0, 1};  // unit, toward the light
    float directed[3] = {};
    float ambient[3] = {};
};

class GridRuntime {
public:
    // Loads the grid of a BSP image held in memory (the bytes are copied as needed, not kept).
    // Returns an empty string on success, else one line prefixed with `name`. A BSP without any
    // grid (no SH grid, empty lump 15) loads with source() == None and samples zero.
    std::string loadFromBsp(const uint8_t* bsp, size_t size, const std::string& name = "");
    // Uses an already decoded SH grid (tools, tests).
    void setGrid(GridSH grid, GridSource source);

    GridSource source() const { return source_; }
    const GridSH& grid() const { return grid_; }

    // Trilinear blend of the 8 surrounding points; positions outside the grid are clamped to its
    // border. For the legacy grid, points with zero ambient (in solid) are left out and the other
    // weights renormalised, as the legacy renderer does. An empty runtime returns zeros.
    GridPointSH sample(const float position[3]) const;

private:
    GridSH grid_;
    std::vector<uint8_t> usable_;  // empty: every point counts
    GridSource source_ = GridSource::None;
};

// max(0, sum_i c_i Y_i(n)) per channel; n must be unit length.
void irradianceAt(const GridPointSH& sample, const float normal[3], float rgb[3]);
AmbientCube toAmbientCube(const GridPointSH& sample);
// Direction from the linear band (luminance-weighted), colours from a least-squares fit of
// ambient + directed * max(0, n.dir) to the SH irradiance over the sphere (documented in
// docs/sh-engine-integration.md).
LegacyLighting toLegacyLighting(const GridPointSH& sample);

}  // namespace q3::sh
