// The options every stage shares (given before the stage switch), and q3map2's list of stages.
#pragma once

#include "common_options.h"
#include "help_text.h"
#include "option_table.h"

#include <vector>

namespace q3::cli {

const OptionTable<CommonOptions>& commonOptionTable();

// Every stage switch of q3map2, in its -help order, all marked unavailable and without options;
// the executable fills in the stages it has.
std::vector<StageDescription> q3map2Stages();

// The -game profiles this build implements.
const std::vector<std::string>& supportedGames();

}  // namespace q3::cli
