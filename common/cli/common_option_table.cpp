#include "common_option_table.h"

#include "ascii_case.h"
#include "option_parser.h"

#include <algorithm>

namespace q3::cli {

namespace {

// Every -game profile of q3map2 2.5.17n (its "-help game" list).
const std::vector<std::string>& q3map2Games() {
    static const std::vector<std::string> games = {
        "quake3", "quakelive", "nexuiz", "xonotic", "tremulous", "unvanquished", "tenebrae", "wolf", "et", "etut",
        "ef",     "qfusion",   "reaction", "darkplaces", "dq", "prophecy", "sof2", "jk2", "ja"};
    return games;
}

void setGame(CommonOptions& o, std::span<const ArgValue> v) {
    const std::string game = toLower(v[0].text);
    const auto& ok = supportedGames();
    if (std::find(ok.begin(), ok.end(), game) != ok.end()) {
        o.game = game;
        return;
    }
    const auto& known = q3map2Games();
    if (std::find(known.begin(), known.end(), game) != known.end())
        throw UsageError("-game " + game + " is a q3map2 game profile this build does not implement yet");
    std::string suggestion = closestName(game, known);
    throw UsageError("-game: unknown game '" + v[0].text + "'" +
                     (suggestion.empty() ? std::string(" (see q3map2 -help game)") : "; did you mean '" + suggestion + "'?"));
}

OptionTable<CommonOptions> buildCommonTable() {
    using O = CommonOptions;
    OptionTable<O> t;
    t.push_back(custom<O>({"-connect"}, {{ArgKind::Text, "address", {}}}, 1, "none",
                          "Talk to a NetRadiant instance using its XML based protocol", kImplemented,
                          [](O& o, std::span<const ArgValue> v) { o.connect = v[0].text; }));
    t.push_back(flag<O>({"-force"}, &O::force, "Allow reading some broken/unsupported BSP files", kImplemented));
    t.push_back(custom<O>({"-fs_basepath"}, {{ArgKind::Text, "path", {}}}, 1, "none",
                          "Sets the given path as main directory of the game (can be used more than once to look "
                          "in multiple paths)",
                          kImplemented, [](O& o, std::span<const ArgValue> v) { o.basePaths.push_back(v[0].text); }));
    t.push_back(custom<O>({"-fs_forbiddenpath"}, {{ArgKind::Text, "pattern", {}}}, 1, "none",
                          "Pattern to ignore directories, pk3, and pk3dir", kNotImplemented,
                          [](O&, std::span<const ArgValue>) {}));
    t.push_back(textValue<O>({"-fs_game"}, &O::fsGame,
                             "Sets extra game directory name to additionally load mod's resources from at higher "
                             "priority",
                             kImplemented, "gamename", "none"));
    t.push_back(textValue<O>({"-fs_basegame"}, &O::baseGame, "Overrides default game directory name", kImplemented,
                             "gamename", "per game"));
    t.push_back(custom<O>({"-fs_home"}, {{ArgKind::Text, "dir", {}}}, 1, "$HOME",
                          "Specifies where the user home directory is on Linux", kNotImplemented,
                          [](O&, std::span<const ArgValue>) {}));
    t.push_back(custom<O>({"-fs_homebase"}, {{ArgKind::Text, "dir", {}}}, 1, "per game",
                          "Specifies game home directory relative to user home directory on Linux", kNotImplemented,
                          [](O&, std::span<const ArgValue>) {}));
    t.push_back(textValue<O>({"-fs_homepath"}, &O::homePath,
                             "Sets the given path as the game home directory name (fs_home + fs_homebase)",
                             kImplemented, "path", "none"));
    t.push_back(custom<O>({"-fs_pakpath"}, {{ArgKind::Text, "path", {}}}, 1, "none",
                          "Specify a package directory (can be used more than once)", kNotImplemented,
                          [](O&, std::span<const ArgValue>) {}));
    t.push_back(custom<O>({"-game"}, {{ArgKind::Text, "gamename", {}}}, 1, CommonOptions{}.game,
                          "Load settings for the given game (quake3 or quakelive)", kImplemented, setGame));
    t.push_back(custom<O>({"-maxmapdrawsurfs"}, {{ArgKind::Int, "N", Range::atLeast(1)}}, 1, "131072",
                          "Sets max amount of mapDrawSurfs, used during .map compilation", kImplemented,
                          [](O& o, std::span<const ArgValue> v) { o.maxMapDrawSurfs = static_cast<int>(v[0].number); }));
    t.push_back(custom<O>({"-subdivisions"}, {{ArgKind::Float, "F", Range::positive()}}, 1, "1",
                          "Multiplier for patch subdivisions quality", kNotImplemented,
                          [](O&, std::span<const ArgValue>) {}));
    t.push_back(custom<O>({"-threads"}, {{ArgKind::Int, "N", Range::between(1, 1024)}}, 1, "one per core",
                          "Number of threads to use", kImplemented,
                          [](O& o, std::span<const ArgValue> v) { o.threads = static_cast<int>(v[0].number); }));
    t.push_back(custom<O>({"-stats"}, {{ArgKind::Text, "FILE.json", {}}}, 1, "none",
                          "Write a machine-readable summary (phase times, rays, luxels, warnings, grid sizes; "
                          "docs/stats-schema.json)",
                          kImplemented, [](O& o, std::span<const ArgValue> v) { o.statsPath = v[0].text; }));
    t.push_back(flag<O>({"-v"}, &O::verbose, "Verbose mode", kImplemented));
    t.push_back(flag<O>({"-werror"}, &O::warningsAsErrors, "Treat warnings as errors: a run that warned exits with 1",
                        kImplemented));
    return t;
}

}  // namespace

const OptionTable<CommonOptions>& commonOptionTable() {
    static const OptionTable<CommonOptions> table = buildCommonTable();
    return table;
}

const std::vector<std::string>& supportedGames() {
    // The profiles the file system (common/vfs) knows; the others of q3map2 are refused by name.
    static const std::vector<std::string> games = {"quake3", "quakelive"};
    return games;
}

std::vector<StageDescription> q3map2Stages() {
    auto stage = [](std::string name, std::string title, std::string file) {
        return StageDescription{std::move(name), std::move(title), std::move(file), false, {}};
    };
    return {
        stage("-bsp", "BSP Stage", "<filename.map>"),
        stage("-vis", "VIS Stage", "<filename.map>"),
        stage("-light", "Light Stage", "<filename.map>"),
        stage("-analyze", "Analyzing BSP-like file structure", "<filename.bsp>"),
        stage("-scale", "Scaling", "<filename.bsp>"),
        stage("-shift", "Shift", "<filename.bsp>"),
        stage("-convert", "Converting & Decompiling", "<filename.bsp>"),
        stage("-export", "Exporting lightmaps", "<filename.bsp>"),
        stage("-import", "Importing lightmaps", "<filename.bsp>"),
        stage("-exportents", "Exporting entities", "<filename.bsp>"),
        stage("-fixaas", "Fixing AAS checksum", "<filename.bsp>"),
        stage("-info", "Get info about BSP file", "<filename.bsp>"),
        stage("-minimap", "MiniMap", "<filename.bsp>"),
        stage("-pk3", "PK3 creation", "<filename.bsp>"),
        stage("-repack", "Maps repack creation", "<filename.bsp>"),
        stage("-json", "BSP json export/import", "<filename.bsp>"),
        stage("-mergebsp", "BSP merge", "<mainBsp.bsp> <bspToinject.bsp>"),
    };
}

}  // namespace q3::cli
