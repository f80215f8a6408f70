// The -light stage: lights a compiled BSP in place (lightmaps, vertex colours, light grid) and
// writes it back atomically.
#pragma once

#include "common_options.h"
#include "light_options.h"
#include "log.h"
#include "run_stats.h"

namespace q3::light {

// Runs the whole stage on common.mapPath (extension forced to .bsp). Returns the process exit code;
// bad input throws the project's one-line exceptions (BspError, FileError, ScriptError, CompileError).
// `stats` (optional) receives the phase times, rays, luxels and grid sizes for -stats.
int runLightStage(const LightOptions& options, const CommonOptions& common, Log& log, RunStats* stats = nullptr);

}  // namespace q3::light
