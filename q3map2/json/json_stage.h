// `q3map2 -json -unpack|-pack MAP.bsp`: the BSP as a folder of JSON files in q3map2's layout,
// and back.
#pragma once

#include "bspfile.h"
#include "common_options.h"
#include "log.h"
#include "option_table.h"

#include <filesystem>

namespace q3::json {

struct JsonOptions {
    bool unpack = false;
    bool pack = false;
    bool useFlagNames = false;   // -useflagnames: flag values from the names in shaders.json
    bool skipFlags = false;      // -skipflags: with -useflagnames, ignore unknown names
    bool lightmapImages = false; // -lightmapimages: lightmap pages as PNG files, not LightBytes.json
};

// The -json stage's options, for the parser and -help.
const cli::OptionTable<JsonOptions>& jsonOptionTable();

// Writes the folder `folder` (normally maps/NAME/ beside the BSP). Every file is written atomically.
void unpackBsp(const bsp::Bsp& bsp, const std::filesystem::path& folder, const JsonOptions& options, Log& log);
// Reads such a folder (ours or q3map2's) into a BSP; throws JsonError/BspError naming file, line,
// column and field. Nothing is written.
bsp::Bsp packFolder(const std::filesystem::path& folder, const JsonOptions& options, Log& log);

// The stage: unpack writes maps/NAME/, pack writes maps/NAME_json.bsp. Returns the exit code.
int runJsonStage(const JsonOptions& options, const CommonOptions& common, Log& log);

}  // namespace q3::json
