// `q3map2 -info MAP.bsp`: the lump counts and sizes of a BSP, printed the way q3map2 does, plus
// the header, BSPX lumps, SH grid statistics and the legacy grid's point count against the one
// engines expect.
#pragma once

#include "bspfile.h"
#include "common_options.h"
#include "log.h"
#include "option_table.h"

#include <cstdint>
#include <string>

namespace q3::info {

// -info has no options of its own; the empty table still drives the parser and -help.
struct InfoOptions {};
const cli::OptionTable<InfoOptions>& infoOptionTable();

// The report for one parsed BSP. `name` and `fileSize` describe the file it came from.
// Throws bsp::BspError when the entity lump or an SH grid lump is malformed.
std::string formatBspInfo(const bsp::Bsp& bsp, const std::string& name, uintmax_t fileSize);

// Reads common.mapPath (never writes anything) and prints the report. Returns the exit code;
// throws FileError/BspError for unreadable or malformed files.
int runInfoStage(const InfoOptions& options, const CommonOptions& common, Log& log);

}  // namespace q3::info
