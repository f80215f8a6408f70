// The SH grid viewers: `-shprobe MAP.bsp X Y Z` prints the interpolated SH grid at a point (nine
// RGB coefficients, the irradiance towards the six axes) beside the legacy grid's value there;
// `-shimage MAP.bsp OUT.png [Z]` draws the probes of one height as small shaded spheres seen from
// above. Both read lump 18 or the BSPX lump LIGHTGRID_SH through the engine runtime of libs/sh.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "common_options.h"
#include "image.h"
#include "log.h"
#include "option_table.h"
#include "sh_grid_runtime.h"

namespace q3::shtools {

struct ShProbeOptions {
    float position[3] = {0, 0, 0};
    bool positionSet = false;  // required: -pos X Y Z or the positional X Y Z
};

struct ShImageOptions {
    std::string output;        // required: -out FILE or the positional OUT.png
    float height = 0;          // world Z of the picture
    bool heightSet = false;    // false: the middle of the grid
    int probePixels = 16;      // side of the square each probe gets
    float exposure = 1;        // tone mapping: 1 - exp(-exposure * irradiance)
};

const cli::OptionTable<ShProbeOptions>& shProbeOptionTable();
const cli::OptionTable<ShImageOptions>& shImageOptionTable();

// The positional forms of the command line, `MAP X Y Z` and `MAP OUT.png [Z]` (everything after the
// stage switch). Returns the map argument; throws cli::UsageError naming what is wrong.
std::string parseShProbeArguments(std::span<const std::string> args, ShProbeOptions& options);
std::string parseShImageArguments(std::span<const std::string> args, ShImageOptions& options);

// What -shprobe prints, computed from a BSP image in memory.
struct ProbeReport {
    float position[3] = {0, 0, 0};
    sh::GridSource source = sh::GridSource::None;
    sh::GridPointSH sh{};                 // interpolated SH irradiance
    sh::AmbientCube shFaces;              // irradiance towards +X -X +Y -Y +Z -Z
    bool hasLegacy = false;
    sh::GridPointSH legacy{};             // the legacy grid at the same point, as SH
    sh::AmbientCube legacyFaces;
    sh::LegacyLighting legacyLighting;    // ambient / directed / direction of the legacy sample
};

// Throws bsp::BspError naming `name` when the BSP is malformed or has no SH grid.
ProbeReport probeBsp(std::span<const uint8_t> bspImage, const float position[3], const std::string& name);
std::vector<std::string> formatProbeReport(const ProbeReport& report);

// Top-down picture of the grid at height z: probe (x, y) is the square at column x, row by-1-y
// (north up), holding a disc shaded by the irradiance for the sphere normal at each pixel.
Image renderProbeImage(const sh::GridRuntime& grid, float z, int probePixels, float exposure);
// The grid's middle height.
float middleHeight(const sh::GridSH& grid);

int runShProbeStage(const ShProbeOptions& options, const CommonOptions& common, Log& log);
int runShImageStage(const ShImageOptions& options, const CommonOptions& common, Log& log);

}  // namespace q3::shtools
