// q3map2's command-line shape: q3map2 [common options] -STAGE [stage options] MAPFILE,
// or q3map2 -help [stage]. Splits the arguments, parses the common options, and leaves the stage's
// own arguments to the stage's table.
#pragma once

#include "common_options.h"
#include "help_text.h"
#include "option_parser.h"
#include "option_table.h"

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace q3::cli {

struct CommandLine {
    bool help = false;
    std::string helpTopic;  // with help: "" for the general text, else a stage name without '-'
    std::string stage;      // "-light"
    std::vector<std::string> stageArgs;  // between the stage switch and the map path
    std::string mapArg;     // the last argument, as given
};

// Splits `args` (argv without the program name) and parses the common options into `common`
// (common.mapPath = the .bsp of the map argument, common.commandLine = the stage and its
// arguments). Throws UsageError; a stage this build lacks is refused here.
CommandLine splitCommandLine(std::span<const std::string> args, const OptionTable<CommonOptions>& commonTable,
                             std::span<const StageDescription> stages, CommonOptions& common);

// The context a stage table is parsed in, for errors that name the stage and the common options.
ParseContext stageParseContext(const std::string& stage, const OptionTable<CommonOptions>& commonTable,
                               std::span<const StageDescription> stages);

// The BSP a map argument designates: "x.bsp" as is, "x.map" -> "x.bsp", "x" -> "x.bsp".
// Any other extension is a usage error.
std::filesystem::path bspPathFor(const std::string& mapArg);

// The help text asked for by a CommandLine with help set. Throws UsageError for an unknown topic.
std::string helpText(const CommandLine& line, const OptionTable<CommonOptions>& commonTable,
                     std::span<const StageDescription> stages);

}  // namespace q3::cli
