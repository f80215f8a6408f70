#include "command_line.h"

#include "ascii_case.h"
#include "common_option_table.h"

#include <algorithm>

namespace q3::cli {

namespace {

const StageDescription* findStage(std::span<const StageDescription> stages, const std::string& token) {
    for (const StageDescription& s : stages)
        if (equalsNoCase(s.name, token)) return &s;
    return nullptr;
}

std::vector<std::string> stageNames(std::span<const StageDescription> stages) {
    std::vector<std::string> names;
    for (const StageDescription& s : stages) names.push_back(s.name);
    return names;
}

// Common options q3map2 takes from anywhere on the command line (its main and path set-up search the
// whole argument list), with the number of values each takes: a stage's options may be followed by
// "-threads 2" as with q3map2 itself.
int anywhereOptionValues(const std::string& token) {
    static const std::pair<const char*, int> kOptions[] = {
        {"-threads", 1},      {"-force", 0},       {"-subdivisions", 1}, {"-game", 1},
        {"-fs_basepath", 1},  {"-fs_game", 1},     {"-fs_basegame", 1},  {"-fs_homepath", 1},
        {"-fs_home", 1},      {"-fs_homebase", 1}, {"-fs_pakpath", 1},   {"-fs_forbiddenpath", 1},
    };
    const std::string t = toLower(token);
    for (const auto& [name, values] : kOptions)
        if (t == name) return values;
    return -1;
}

bool isHelpSwitch(const std::string& token) {
    std::string t = toLower(token);
    return t == "-help" || t == "--help" || t == "-h";
}

}  // namespace

ParseContext stageParseContext(const std::string& stage, const OptionTable<CommonOptions>& commonTable,
                               std::span<const StageDescription> stages) {
    return ParseContext{stage, describe(commonTable), stageNames(stages)};
}

std::filesystem::path bspPathFor(const std::string& mapArg) {
    std::filesystem::path path(mapArg);
    std::string extension = toLower(path.extension().string());
    if (extension == ".bsp") return path;
    if (extension == ".map" || extension == ".reg" || extension == ".ent")
        return std::filesystem::path(path).replace_extension(".bsp");
    if (extension.empty()) return std::filesystem::path(mapArg + ".bsp");
    throw UsageError("map file '" + mapArg + "' must end in .bsp, .map, .reg or .ent (or have no extension)");
}

CommandLine splitCommandLine(std::span<const std::string> args, const OptionTable<CommonOptions>& commonTable,
                             std::span<const StageDescription> stages, CommonOptions& common) {
    CommandLine line;
    if (!args.empty() && isHelpSwitch(args[0])) {
        if (args.size() > 2) throw UsageError("-help takes at most one stage name, got '" + args[2] + "'");
        line.help = true;
        if (args.size() == 2) line.helpTopic = args[1][0] == '-' ? args[1].substr(1) : args[1];
        return line;
    }

    // Common options up to the stage switch.
    std::vector<OptionInfo> commonInfos = describe(commonTable);
    size_t pos = 0;
    while (pos < args.size() && !findStage(stages, args[pos])) ++pos;
    ParseContext before{"", commonInfos, stageNames(stages)};
    // Without a stage switch q3map2 compiles the map (-bsp): every common option is taken out, the
    // other arguments before the map file are -bsp's.
    const StageDescription* bsp = findStage(stages, "-bsp");
    if (pos == args.size() && bsp && bsp->available && !args.empty() && !args.back().empty() && args.back()[0] != '-') {
        line.stage = bsp->name;
        line.mapArg = args.back();
        std::vector<std::string> moved;
        for (size_t i = 0; i + 1 < args.size(); ++i) {
            const int option = findOption(commonInfos, args[i]);
            if (option < 0) {
                // A mistyped stage switch is likelier than a mistyped -bsp option: name the stage.
                if (args[i][0] == '-' && findOption(bsp->options, args[i]) < 0) {
                    const std::string suggestion = closestName(args[i], stageNames(stages));
                    if (!suggestion.empty())
                        throw UsageError("unknown option '" + args[i] + "'; did you mean '" + suggestion + "'?");
                }
                line.stageArgs.push_back(args[i]);
                continue;
            }
            moved.push_back(args[i]);
            for (size_t v = 0; v < commonInfos[size_t(option)].args.size() && i + 2 < args.size(); ++v)
                moved.push_back(args[++i]);
        }
        parseOptions(commonTable, moved, before, common);
        common.mapPath = bspPathFor(line.mapArg);
        common.mapArgument = line.mapArg;
        common.commandLine = bsp->name;
        for (const std::string& a : line.stageArgs) common.commandLine += " " + a;
        return line;
    }
    if (pos == args.size()) {
        // A mistyped stage switch shows up as an unknown option; name it rather than the missing stage.
        std::span<const std::string> leading = args;
        if (!leading.empty() && !leading.back().empty() && leading.back()[0] != '-')
            leading = leading.first(leading.size() - 1);
        parseArguments(commonInfos, leading, before);
        throw UsageError("no stage given: expected a stage switch such as -light or -info before the map file "
                         "(see q3map2 -help)");
    }
    parseOptions(commonTable, args.subspan(0, pos), before, common);

    const StageDescription& stage = *findStage(stages, args[pos]);
    if (!stage.available) throw UsageError(stage.name + " is a q3map2 stage this build does not implement yet");
    line.stage = stage.name;

    std::span<const std::string> rest = args.subspan(pos + 1);
    if (rest.empty() || rest.back().empty() || rest.back()[0] == '-')
        throw UsageError(stage.name + " needs a map file as its last argument (" + stage.name + " [options] " +
                         stage.fileUsage + ")");
    line.mapArg = rest.back();
    std::vector<std::string> moved;
    for (size_t i = 0; i + 1 < rest.size(); ++i) {
        const int values = anywhereOptionValues(rest[i]);
        if (values < 0 || findOption(commonInfos, rest[i]) < 0) {
            line.stageArgs.push_back(rest[i]);
            continue;
        }
        moved.push_back(rest[i]);
        for (int v = 0; v < values && i + 2 < rest.size(); ++v) moved.push_back(rest[++i]);
    }
    if (!moved.empty()) parseOptions(commonTable, moved, before, common);

    common.mapPath = bspPathFor(line.mapArg);
    common.mapArgument = line.mapArg;
    common.commandLine = stage.name;
    for (const std::string& a : line.stageArgs) common.commandLine += " " + a;
    return line;
}

std::string helpText(const CommandLine& line, const OptionTable<CommonOptions>& commonTable,
                     std::span<const StageDescription> stages) {
    std::vector<OptionInfo> common = describe(commonTable);
    if (line.helpTopic.empty()) return formatGeneralHelp(common, stages);
    if (toLower(line.helpTopic) == "game") {
        std::string text = "Available games:\n";
        for (const std::string& game : supportedGames()) text += "  " + game + "\n";
        return text;
    }
    if (const StageDescription* stage = findStage(stages, "-" + line.helpTopic))
        return formatStageHelp(common, *stage);
    std::vector<std::string> names;
    for (const StageDescription& s : stages) names.push_back(s.name.substr(1));
    std::string suggestion = closestName(line.helpTopic, names);
    throw UsageError("no help for unknown stage '" + line.helpTopic + "'" +
                     (suggestion.empty() ? std::string(" (see q3map2 -help)") : "; did you mean '" + suggestion + "'?"));
}

}  // namespace q3::cli
