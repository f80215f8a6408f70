// `q3map2 -vis MAP.bsp`: reads MAP.prt (written by -bsp) and stores the potentially visible set
// of every cluster in the BSP's visibility lump. Every other lump is kept byte for byte, except
// worldspawn's recorded command line; the BSP is replaced atomically and the .prt deleted unless
// -saveprt is given.
#pragma once

#include "common_options.h"
#include "log.h"
#include "option_table.h"

namespace q3::vis {

struct VisOptions {
    bool fast = false;          // -fast: the base flood only
    bool merge = false;         // -merge: merge leaves, then coplanar portals
    bool mergePortals = false;  // -mergeportals: only coplanar portals
    bool hint = false;          // -hint: -merge that never merges through hint portals
    bool noPassage = false;     // -nopassage
    bool passageOnly = false;   // -passageOnly
    bool noSort = false;        // -nosort
    bool savePrt = false;       // -saveprt
    bool clusterHistogram = false;  // -v after -vis: how many clusters see how many
};

const cli::OptionTable<VisOptions>& visOptionTable();

// Returns the exit code; throws PortalFileError, bsp::BspError, FileError or CompileError.
int runVisStage(const VisOptions& options, const CommonOptions& common, Log& log);

}  // namespace q3::vis
