// The q3map2 executable: parses the command line, applies the common options and runs one stage.
// Exit codes: 0 success, 1 compile failure ("ERROR: <message>"), 2 usage error.
#include "ascii_case.h"
#include "bsp_stage.h"
#include "command_line.h"
#include "feedback_log.h"
#include "run_stats.h"
#include "sh_tools.h"
#include "common_option_table.h"
#include "info_stage.h"
#include "light_options.h"
#include "log.h"

#include "json_stage.h"
#include "light_stage.h"
#include "vis_stage.h"
#include "lightmap_export.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace {

using q3::cli::UsageError;


// q3map2's stage list, with the stages of this build filled in.
std::vector<q3::cli::StageDescription> stageList() {
    std::vector<q3::cli::StageDescription> stages = q3::cli::q3map2Stages();
    for (q3::cli::StageDescription& s : stages) {
        if (s.name == "-bsp") {
            s.available = true;
            s.options = q3::cli::describe(q3::bspstage::bspOptionTable());
        } else if (s.name == "-info") {
            s.available = true;
            s.options = q3::cli::describe(q3::info::infoOptionTable());
        } else if (s.name == "-vis") {
            s.available = true;
            s.options = q3::cli::describe(q3::vis::visOptionTable());
        } else if (s.name == "-light") {
            s.available = true;
            s.options = q3::cli::describe(q3::light::lightOptionTable());
        } else if (s.name == "-export" || s.name == "-import") {
            s.available = true;
            s.options = q3::cli::describe(q3::light::pictureStageOptionTable());
        } else if (s.name == "-json") {
            s.available = true;
            s.options = q3::cli::describe(q3::json::jsonOptionTable());
        }
    }
    stages.push_back({"-shprobe", "SH grid probe", "<filename.bsp> X Y Z", true,
                      q3::cli::describe(q3::shtools::shProbeOptionTable())});
    stages.push_back({"-shimage", "SH grid picture", "<filename.bsp> OUT.png [Z]", true,
                      q3::cli::describe(q3::shtools::shImageOptionTable())});
    stages.push_back({"-shcubemap",
                      "SH cubemap projection (faces seen from inside, BSP axes, Z up; right x down = outward: "
                      "+X right -Y down -Z, -X right +Y down -Z, +Y right +X down -Z, -Y right -X down -Z, "
                      "+Z right -Y down +X, -Z right -Y down -X)",
                      "PX NX PY NY PZ NZ", true, q3::cli::describe(q3::shtools::shCubemapOptionTable())});
    return stages;
}

// The SH viewers take their map first (`-shprobe MAP X Y Z`, `-shimage MAP OUT.png [Z]`); rewritten
// here to the common shape (`-shprobe MAP`) with the positional values parsed into `probe`/`image`.
std::vector<std::string> takePositionalViewerArgs(std::vector<std::string> args, q3::shtools::ShProbeOptions& probe,
                                                  q3::shtools::ShImageOptions& image) {
    auto it = std::find_if(args.begin(), args.end(), [](const std::string& a) { return a == "-shprobe" || a == "-shimage"; });
    if (it == args.end() || it + 1 == args.end() || (*(it + 1))[0] == '-') return args;
    std::span<const std::string> rest(&*(it + 1), static_cast<size_t>(args.end() - it - 1));
    std::string map = *it == "-shprobe" ? q3::shtools::parseShProbeArguments(rest, probe)
                                        : q3::shtools::parseShImageArguments(rest, image);
    args.erase(it + 1, args.end());
    args.push_back(map);
    return args;
}

// `-help [stage]` comes first on the command line (any case, also --help and -h).
bool isHelpRequest(const std::vector<std::string>& args) {
    if (args.empty()) return false;
    const std::string first = q3::toLower(args.front());
    return first == "-help" || first == "--help" || first == "-h";
}

template <class Options>
Options parseStageOptions(const q3::cli::OptionTable<Options>& table, const q3::cli::CommandLine& line,
                          const std::vector<q3::cli::StageDescription>& stages) {
    Options options{};
    q3::cli::ParseContext context = q3::cli::stageParseContext(line.stage, q3::cli::commonOptionTable(), stages);
    q3::cli::parseOptions(table, line.stageArgs, context, options);
    return options;
}

int runStage(const q3::cli::CommandLine& line, const q3::CommonOptions& common,
             const std::vector<q3::cli::StageDescription>& stages, q3::Log& log, q3::RunStats& stats,
             q3::shtools::ShProbeOptions probe, q3::shtools::ShImageOptions image, q3::FeedbackStream* feedback);

// `common` and `feedback` live in main so that a failure can still reach NetRadiant.
int run(const std::vector<std::string>& rawArgs, q3::Log& log, q3::CommonOptions& common,
        std::shared_ptr<q3::FeedbackStream>& feedback) {
    std::vector<q3::cli::StageDescription> stages = stageList();
    q3::shtools::ShProbeOptions probe;
    q3::shtools::ShImageOptions image;
    // -shcubemap takes six images instead of a map file: run before the map-file command line.
    if (auto it = std::find(rawArgs.begin(), rawArgs.end(), "-shcubemap");
        it != rawArgs.end() && !isHelpRequest(rawArgs)) {
        q3::cli::ParseContext context = q3::cli::stageParseContext("-shcubemap", q3::cli::commonOptionTable(), stages);
        q3::cli::parseOptions(q3::cli::commonOptionTable(), std::span(rawArgs.begin(), it), context, common);
        log.setVerbose(common.verbose);
        return q3::shtools::runShCubemapCommand(std::span(it + 1, rawArgs.end()), context, log);
    }
    std::vector<std::string> args = takePositionalViewerArgs(rawArgs, probe, image);
    q3::cli::CommandLine line = q3::cli::splitCommandLine(args, q3::cli::commonOptionTable(), stages, common);
    if (line.help) {
        std::string text = q3::cli::helpText(line, q3::cli::commonOptionTable(), stages);
        std::fwrite(text.data(), 1, text.size(), stdout);
        return 0;
    }
    log.setVerbose(common.verbose);
    if (!common.connect.empty()) feedback = q3::connectNetRadiant(common.connect, log);
    std::optional<tbb::global_control> threads;
    if (common.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(common.threads));

    auto start = std::chrono::steady_clock::now();
    q3::RunStats stats;
    int status = runStage(line, common, stages, log, stats, probe, image, feedback.get());
    if (status == 0 && common.warningsAsErrors && log.warningCount() > 0) {
        log.error(std::to_string(log.warningCount()) + " warning(s) with -werror");
        status = 1;
    }
    if (!common.statsPath.empty()) {
        stats.stage = line.stage.substr(1);
        stats.map = common.mapPath.string();
        stats.threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
        stats.totalSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats.warnings = log.warningCount();
        q3::writeRunStats(common.statsPath, stats);
    }
    return status;
}

int runStage(const q3::cli::CommandLine& line, const q3::CommonOptions& common,
             const std::vector<q3::cli::StageDescription>& stages, q3::Log& log, q3::RunStats& stats,
             q3::shtools::ShProbeOptions probe, q3::shtools::ShImageOptions image, q3::FeedbackStream* feedback) {
    // Each stage checks all of its options before any work starts.
    if (line.stage == "-bsp") {
        auto options = parseStageOptions(q3::bspstage::bspOptionTable(), line, stages);
        return q3::bspstage::runBspStage(options, common, log, feedback);
    }
    if (line.stage == "-info") {
        auto options = parseStageOptions(q3::info::infoOptionTable(), line, stages);
        return q3::info::runInfoStage(options, common, log);
    }
    if (line.stage == "-vis") {
        auto options = parseStageOptions(q3::vis::visOptionTable(), line, stages);
        return q3::vis::runVisStage(options, common, log);
    }
    if (line.stage == "-light") {
        auto options = parseStageOptions(q3::light::lightOptionTable(), line, stages);
        return q3::light::runLightStage(options, common, log, &stats);
    }
    if (line.stage == "-shprobe") {
        q3::cli::ParseContext context = q3::cli::stageParseContext(line.stage, q3::cli::commonOptionTable(), stages);
        q3::cli::parseOptions(q3::shtools::shProbeOptionTable(), line.stageArgs, context, probe);
        return q3::shtools::runShProbeStage(probe, common, log);
    }
    if (line.stage == "-shimage") {
        q3::cli::ParseContext context = q3::cli::stageParseContext(line.stage, q3::cli::commonOptionTable(), stages);
        q3::cli::parseOptions(q3::shtools::shImageOptionTable(), line.stageArgs, context, image);
        return q3::shtools::runShImageStage(image, common, log);
    }
    if (line.stage == "-export" || line.stage == "-import") {
        parseStageOptions(q3::light::pictureStageOptionTable(), line, stages);
        return line.stage == "-export" ? q3::light::runExportStage(common, log)
                                        : q3::light::runImportStage(common, log);
    }
    if (line.stage == "-json") {
        auto options = parseStageOptions(q3::json::jsonOptionTable(), line, stages);
        return q3::json::runJsonStage(options, common, log);
    }
    // splitCommandLine refuses unavailable stages, so this is only reached if the list and the
    // dispatch above disagree.
    throw UsageError(line.stage + " is a q3map2 stage this build does not implement yet");
}

// Prints the one-line error; when the command line got as far as -connect (a stage or a stage
// option this build lacks, say) the editor is told too, since it shows only what it receives.
void reportFailure(q3::Log& log, const q3::CommonOptions& common, std::shared_ptr<q3::FeedbackStream>& feedback,
                   const char* message) {
    if (!feedback && !common.connect.empty()) feedback = q3::connectNetRadiant(common.connect, log);
    log.error(message);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    q3::Log log;
    q3::CommonOptions common;  // filled as far as the command line parsed
    std::shared_ptr<q3::FeedbackStream> feedback;
#if !defined(__SANITIZE_ADDRESS__)
    // Sanitizer builds free everything and leave through the runtime's exit, so that their leak
    // check sees the whole run.
    common.processEndsAfterStage = true;
#endif
    try {
        const int status = run(args, log, common, feedback);
        if (common.processEndsAfterStage && !feedback) {
            // The stage's output is written and renamed; what is left is freeing, which the
            // process's end does at once. The editor's connection, when there is one, closes in order.
            std::fflush(nullptr);
            std::_Exit(status);
        }
        return status;
    } catch (const UsageError& e) {
        reportFailure(log, common, feedback, e.what());
        return 2;
    } catch (const std::exception& e) {
        reportFailure(log, common, feedback, e.what());
        return 1;
    } catch (...) {
        reportFailure(log, common, feedback, "unexpected failure");
        return 1;
    }
}
