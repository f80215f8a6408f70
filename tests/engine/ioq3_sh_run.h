// ioquake3 with the SH light grid patch (tools/engine/ioq3-sh): building the patched renderer,
// compiling maps with this build's stages, rendering a player model in third person with the SH
// grid, the legacy grid or no model, and reading what the patched renderer reports.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine_picture.h"
#include "engine_run.h"
#include "image.h"

namespace q3::enginetest {

// The ioquake3 client copy beside the patched renderers (tools/engine/ioq3-sh/build.sh, cached in
// the data cache). Empty with `why` set when something the build needs is missing here (the
// tests then skip and say so); a build that fails adds a test failure.
std::filesystem::path patchedIoq3(std::string& why);

// Runs one q3map2 stage in gameDir: `q3map2 -fs_basepath <OpenArena> -fs_game baseoa STAGE... FILE`.
// Adds a test failure and throws when it fails.
void runStage(const std::filesystem::path& gameDir, const std::vector<std::string>& stage, const std::string& file);
// -bsp -meta, -vis -fast, -light -fast -sh -shbspx on gameDir/maps/NAME.map; returns the BSP.
std::filesystem::path compileWithShBspx(const std::filesystem::path& gameDir, const std::string& name);

// How the model is lit in a shot.
enum class GridChoice { Sh, Legacy, NoModel };

struct Shot {
    Image image;
    std::string log;  // the engine's console log
};

// A strict q3-screenshot `third` shot of `bsp` from `view` ("X Y Z YAW") by the patched client:
// r_shGrid 1, r_shGrid 0, or r_drawentities 0 for the picture without the model. Extra console
// lines are appended; `settle` is q3-screenshot's -d. Adds a failure and throws when no shot is written.
Shot shootThird(const std::filesystem::path& ioq3, const std::filesystem::path& bsp, const std::string& view,
                GridChoice grid, const std::filesystem::path& dir, const std::vector<std::string>& extraLines = {},
                const std::string& settle = "1.5");

// The model in a shot: the pixels that differ from the shot without it.
MaskedStats modelStats(const Shot& withModel, const Shot& withoutModel);

// The SH sample the patched renderer printed with r_debuglight ("shgrid at X Y Z = 27 floats"),
// and the largest difference from libs/sh's runtime sampling the same file at the same point.
struct RendererSample {
    float position[3];
    float coeffs[27];
};
std::vector<RendererSample> rendererSamples(const std::string& log);
double largestRuntimeDifference(const std::filesystem::path& bsp, const RendererSample& sample);

// The mean over all normals of the light libs/sh's runtime samples at `position` in `bsp` (format
// units, averaged over the channels): the SH grid when the file has one, else lump 15 converted.
double gridSphereMean(const std::filesystem::path& bsp, const float position[3]);

// Frame times (ms, com_speeds' "all:") the client printed, without the first `skip` frames.
std::vector<double> frameTimes(const std::string& log, size_t skip);

}  // namespace q3::enginetest
