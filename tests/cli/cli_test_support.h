// Shared helpers of the command-line tests.
#pragma once

#include "command_line.h"
#include "light_options.h"

#include <functional>
#include <string>
#include <vector>

namespace q3::test {

// The stage list the executable builds: -info (no options) and -light available.
std::vector<cli::StageDescription> testStages();

// Parses light-stage arguments the way main does after the stage switch.
light::LightOptions parseLight(const std::vector<std::string>& args);

// Splits a whole command line (argv without the program name).
cli::CommandLine split(const std::vector<std::string>& args, CommonOptions* common = nullptr);

// The message of the UsageError `action` throws, or "<no error>".
std::string usageErrorOf(const std::function<void()>& action);

}  // namespace q3::test
