// The SH grid viewers: `-shprobe MAP.bsp X Y Z` prints the interpolated SH grid at a point (nine
// RGB coefficients, the irradiance towards the six axes) beside the legacy grid's value there;
// `-shimage MAP.bsp OUT.png [Z]` draws the probes of one height as small shaded spheres seen from
// above. Both read lump 18 or the BSPX lump LIGHTGRID_SH through the engine runtime of libs/sh.
#pragma once

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "common_options.h"
#include "image.h"
#include "light_cache.h"
#include "log.h"
#include "option_table.h"
#include "option_parser.h"
#include "sh_cubemap.h"
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
    // The light cache's answer when the BSP has a WORLDLIGHTS lump (-light -worldlights).
    bool hasWorldLights = false;
    sh::LightCacheResult cache;
    std::vector<sh::WorldLight> cacheLights;  // the lump's records, cache.local indexes them
};

// Throws bsp::BspError naming `name` when the BSP is malformed or has no SH grid.
ProbeReport probeBsp(std::span<const uint8_t> bspImage, const float position[3], const std::string& name);
std::vector<std::string> formatProbeReport(const ProbeReport& report);

// A linear irradiance as a display byte: 1 - exp(-exposure * irradiance) (keeps HDR values apart
// instead of clipping them), then a monitor's 1/2.2 gamma.
uint8_t toDisplay(float irradiance, float exposure);
// The pixels of a `cell`-pixel square that show a unit sphere seen from above (image right = +X,
// image up = +Y, the visible half faces +Z), each with its sphere normal.
struct DiscPixel {
    int x, y;
    float normal[3];
};
std::vector<DiscPixel> sphereDisc(int cell);

// Top-down picture of the grid at height z: probe (x, y) is the square at column x, row by-1-y
// (north up), holding a disc shaded by the irradiance for the sphere normal at each pixel.
Image renderProbeImage(const sh::GridRuntime& grid, float z, int probePixels, float exposure);
// The grid's middle height.
float middleHeight(const sh::GridSH& grid);

// -shcubemap [options] PX NX PY NY PZ NZ: six face images (any format the image library decodes; the
// face orientation of sh_cubemap.h) projected onto L2 SH radiance and convolved to irradiance.
struct ShCubemapOptions {
    std::array<std::string, 6> faces;  // +X -X +Y -Y +Z -Z
    float scale = 1;                   // radiance = byte / 255 * scale
};
const cli::OptionTable<ShCubemapOptions>& shCubemapOptionTable();
struct CubemapReport {
    int faceSize = 0;
    sh::SH9Color radiance;
    sh::SH9Color irradiance;
};
// A decoded image as a face (bytes / 255 * scale); FileError naming `name` unless it is square.
sh::CubeFaceImage toCubeFace(const Image& image, float scale, const std::string& name, const char* faceName);
// Reads and decodes the six files; FileError naming the file for unreadable, non-square or
// mismatched faces.
sh::Cubemap loadCubemap(const std::array<std::string, 6>& files, float scale);
CubemapReport projectCubemapFiles(const std::array<std::string, 6>& files, float scale);
std::vector<std::string> formatCubemapReport(const CubemapReport& report);
// Everything after the -shcubemap switch: options, then the six faces.
int runShCubemapCommand(std::span<const std::string> stageArgs, const cli::ParseContext& context, Log& log);

int runShProbeStage(const ShProbeOptions& options, const CommonOptions& common, Log& log);
int runShImageStage(const ShImageOptions& options, const CommonOptions& common, Log& log);

}  // namespace q3::shtools
