// The -help text, generated from the option tables (the same tables the parser uses).
#pragma once

#include "option_table.h"

#include <span>
#include <string>
#include <vector>

namespace q3::cli {

// A stage switch as listed by -help and accepted (or refused as not built) by the command line.
struct StageDescription {
    std::string name;       // "-light"
    std::string title;      // "Light Stage"
    std::string fileUsage;  // "<filename.bsp>"
    bool available = false;  // false: a q3map2 stage this build does not have yet
    std::vector<OptionInfo> options;
};

// One option as a help entry: "  -name <A>, -alias <A>   text (default: x)", wrapped to 80 columns.
std::string formatOptionEntry(const OptionInfo& option);

// `q3map2 -help`: usage, common options, list of stages.
std::string formatGeneralHelp(std::span<const OptionInfo> common, std::span<const StageDescription> stages);
// `q3map2 -help light`: usage, common options, the stage's own options.
std::string formatStageHelp(std::span<const OptionInfo> common, const StageDescription& stage);

}  // namespace q3::cli
