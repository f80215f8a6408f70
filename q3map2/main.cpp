// The q3map2 executable: parses the command line, applies the common options and runs one stage.
// Exit codes: 0 success, 1 compile failure ("ERROR: <message>"), 2 usage error.
#include "command_line.h"
#include "common_option_table.h"
#include "info_stage.h"
#include "light_options.h"
#include "log.h"

#if Q3MAP_HAVE_LIGHT_STAGE
#include "light_stage.h"
#endif
#if Q3MAP_HAVE_JSON_STAGE
#include "json_stage.h"
#endif

#include <tbb/global_control.h>

#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace {

using q3::cli::UsageError;

#if Q3MAP_HAVE_JSON_STAGE
const q3::cli::OptionTable<q3::json::JsonOptions>& jsonOptionTable() {
    using O = q3::json::JsonOptions;
    using q3::cli::flag;
    using q3::cli::kImplemented;
    static const q3::cli::OptionTable<O> table = {
        flag<O>({"-unpack"}, &O::unpack, "Unpack the BSP to JSON files", kImplemented),
        flag<O>({"-pack"}, &O::pack, "Pack the JSON files back to a BSP", kImplemented),
        flag<O>({"-useflagnames"}, &O::useFlagNames,
                "While packing, take surface and content flag values from their names in shaders.json",
                kImplemented),
        flag<O>({"-skipflags"}, &O::skipFlags, "With -useflagnames, skip unknown flag names", kImplemented),
        flag<O>({"-lightmapimages"}, &O::lightmapImages, "Lightmap pages as PNG files instead of LightBytes.json",
                kImplemented),
    };
    return table;
}
#endif

// q3map2's stage list, with the stages of this build filled in.
std::vector<q3::cli::StageDescription> stageList() {
    std::vector<q3::cli::StageDescription> stages = q3::cli::q3map2Stages();
    for (q3::cli::StageDescription& s : stages) {
        if (s.name == "-info") {
            s.available = true;
            s.options = q3::cli::describe(q3::info::infoOptionTable());
        } else if (s.name == "-light") {
            // The table is listed even before the stage runs, so -help light documents it.
            s.available = Q3MAP_HAVE_LIGHT_STAGE != 0;
            s.options = q3::cli::describe(q3::light::lightOptionTable());
        } else if (s.name == "-json") {
#if Q3MAP_HAVE_JSON_STAGE
            s.available = true;
            s.options = q3::cli::describe(jsonOptionTable());
#endif
        }
    }
    return stages;
}

template <class Options>
Options parseStageOptions(const q3::cli::OptionTable<Options>& table, const q3::cli::CommandLine& line,
                          const std::vector<q3::cli::StageDescription>& stages) {
    Options options{};
    q3::cli::ParseContext context = q3::cli::stageParseContext(line.stage, q3::cli::commonOptionTable(), stages);
    q3::cli::parseOptions(table, line.stageArgs, context, options);
    return options;
}

int run(const std::vector<std::string>& args, q3::Log& log) {
    std::vector<q3::cli::StageDescription> stages = stageList();
    q3::CommonOptions common;
    q3::cli::CommandLine line = q3::cli::splitCommandLine(args, q3::cli::commonOptionTable(), stages, common);
    if (line.help) {
        std::string text = q3::cli::helpText(line, q3::cli::commonOptionTable(), stages);
        std::fwrite(text.data(), 1, text.size(), stdout);
        return 0;
    }
    log.setVerbose(common.verbose);
    std::optional<tbb::global_control> threads;
    if (common.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(common.threads));

    // Each stage checks all of its options before any work starts.
    if (line.stage == "-info") {
        auto options = parseStageOptions(q3::info::infoOptionTable(), line, stages);
        return q3::info::runInfoStage(options, common, log);
    }
#if Q3MAP_HAVE_LIGHT_STAGE
    if (line.stage == "-light") {
        auto options = parseStageOptions(q3::light::lightOptionTable(), line, stages);
        return q3::light::runLightStage(options, common, log);
    }
#endif
#if Q3MAP_HAVE_JSON_STAGE
    if (line.stage == "-json") {
        auto options = parseStageOptions(jsonOptionTable(), line, stages);
        return q3::json::runJsonStage(options, common, log);
    }
#endif
    // splitCommandLine refuses unavailable stages, so this is only reached if the list and the
    // dispatch above disagree.
    throw UsageError(line.stage + " is a q3map2 stage this build does not implement yet");
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    q3::Log log;
    try {
        return run(args, log);
    } catch (const UsageError& e) {
        log.error(e.what());
        return 2;
    } catch (const std::exception& e) {
        log.error(e.what());
        return 1;
    } catch (...) {
        log.error("unexpected failure");
        return 1;
    }
}
