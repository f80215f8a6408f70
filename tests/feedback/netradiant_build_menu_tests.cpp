// docs/netradiant/build_menu.xml: well-formed, in NetRadiant's build-menu layout (<project
// version="2.0"> with <var> and <build name> holding <command>s), with the presets the docs promise.
// Every command line is expanded the way NetRadiant expands it and run through the compiler's own
// command-line parser: it either parses, or is refused only because a stage or option is not in
// this build yet, and docs/netradiant/README.md lists exactly those per preset.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "command_line.h"
#include "bsp_options.h"
#include "common_option_table.h"
#include "light_options.h"
#include "vis_stage.h"

namespace {

const std::filesystem::path kDocs = std::filesystem::path(Q3MAP_SOURCE_DIR) / "docs/netradiant";
const std::string kNotYet = " is a q3map2 stage this build does not implement yet";
const std::string kOptionNotYet = " is a q3map2 option this build does not implement yet";

struct BuildEntry {
    std::string name;
    std::vector<std::string> commands;
};

struct BuildMenu {
    std::string version;
    std::vector<std::pair<std::string, std::string>> vars;  // name, text (with <cond> contents)
    std::vector<BuildEntry> builds;
};

std::string attribute(xmlNodePtr node, const char* name) {
    xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
    std::string out = value ? reinterpret_cast<const char*>(value) : "";
    xmlFree(value);
    return out;
}

// The text of a node; <cond> parts are included, as NetRadiant does when their variable is set
// (monitoring on, a mod folder selected).
std::string allText(xmlNodePtr node) {
    xmlChar* text = xmlNodeGetContent(node);
    std::string out = text ? reinterpret_cast<const char*>(text) : "";
    xmlFree(text);
    return out;
}

bool named(xmlNodePtr node, const char* name) {
    return node->type == XML_ELEMENT_NODE && xmlStrcmp(node->name, reinterpret_cast<const xmlChar*>(name)) == 0;
}

BuildMenu readMenu() {
    BuildMenu menu;
    const std::filesystem::path path = kDocs / "build_menu.xml";
    xmlDocPtr doc = xmlReadFile(path.c_str(), nullptr, XML_PARSE_NONET);
    EXPECT_NE(doc, nullptr) << path << " is not well-formed XML";
    if (!doc) return menu;
    xmlNodePtr root = xmlDocGetRootElement(doc);
    EXPECT_TRUE(named(root, "project"));
    menu.version = attribute(root, "version");
    for (xmlNodePtr node = root->children; node; node = node->next) {
        if (named(node, "var")) {
            menu.vars.emplace_back(attribute(node, "name"), allText(node));
        } else if (named(node, "build")) {
            BuildEntry entry{attribute(node, "name"), {}};
            for (xmlNodePtr c = node->children; c; c = c->next) {
                if (named(c, "command")) entry.commands.push_back(allText(c));
                else EXPECT_NE(c->type, XML_ELEMENT_NODE) << "unexpected element in <build>";
            }
            menu.builds.push_back(entry);
        } else {
            EXPECT_NE(node->type, XML_ELEMENT_NODE) << "unexpected element " << node->name;
        }
    }
    xmlFreeDoc(doc);
    return menu;
}

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
}

// A command as NetRadiant runs it: menu variables, then the editor's own ones, replaced.
std::string expand(std::string command, const BuildMenu& menu) {
    for (const auto& [name, value] : menu.vars) replaceAll(command, "[" + name + "]", value);
    const std::map<std::string, std::string> editor = {
        {"[RadiantPath]", "/opt/netradiant/"},        {"[ExecutableType]", "x86_64"},
        {"[EnginePath]", "/games/openarena/"},        {"[GameName]", "baseoa"},
        {"[MonitorAddress]", "127.0.0.1:39000"},     {"[MapFile]", "/games/openarena/baseoa/maps/my map.map"}};
    for (const auto& [name, value] : editor) replaceAll(command, name, value);
    return command;
}

// Shell-style words: blanks separate, double quotes group.
std::vector<std::string> shellWords(const std::string& line) {
    std::vector<std::string> words;
    std::string word;
    bool inWord = false, quoted = false;
    for (char c : line) {
        if (c == '"') {
            quoted = !quoted;
            inWord = true;
        } else if (c == ' ' && !quoted) {
            if (inWord) words.push_back(word);
            word.clear();
            inWord = false;
        } else {
            word += c;
            inWord = true;
        }
    }
    EXPECT_FALSE(quoted) << "unbalanced quotes: " << line;
    if (inWord) words.push_back(word);
    return words;
}

// The stage list of the executable, as far as the menu uses it.
std::vector<q3::cli::StageDescription> executableStages() {
    std::vector<q3::cli::StageDescription> stages = q3::cli::q3map2Stages();
    for (q3::cli::StageDescription& s : stages)
        if (s.name == "-bsp" || s.name == "-light" || s.name == "-vis" || s.name == "-info" || s.name == "-json")
            s.available = true;
    for (q3::cli::StageDescription& s : stages) {
        if (s.name == "-bsp") s.options = q3::cli::describe(q3::bspstage::bspOptionTable());
        if (s.name == "-light") s.options = q3::cli::describe(q3::light::lightOptionTable());
        if (s.name == "-vis") s.options = q3::cli::describe(q3::vis::visOptionTable());
    }
    return stages;
}

// Parses argv (without the executable) as main does. Returns "" when it parses, else the
// UsageError's message.
std::string parseLikeMain(const std::vector<std::string>& args) {
    std::vector<q3::cli::StageDescription> stages = executableStages();
    try {
        q3::CommonOptions common;
        q3::cli::CommandLine line = q3::cli::splitCommandLine(args, q3::cli::commonOptionTable(), stages, common);
        EXPECT_TRUE(line.stage == "-bsp" || line.stage == "-light" || line.stage == "-vis") << "the menu's stages";
        const q3::cli::ParseContext context = q3::cli::stageParseContext(line.stage, q3::cli::commonOptionTable(), stages);
        if (line.stage == "-bsp") {
            q3::bspstage::BspOptions options;
            q3::cli::parseOptions(q3::bspstage::bspOptionTable(), line.stageArgs, context, options);
        } else if (line.stage == "-vis") {
            q3::vis::VisOptions options;
            q3::cli::parseOptions(q3::vis::visOptionTable(), line.stageArgs, context, options);
        } else {
            q3::light::LightOptions options;
            q3::cli::parseOptions(q3::light::lightOptionTable(), line.stageArgs, context, options);
        }
        EXPECT_EQ(common.connect, "127.0.0.1:39000");
        EXPECT_EQ(common.basePaths, std::vector<std::string>{"/games/openarena/"});
        EXPECT_EQ(common.fsGame, "baseoa");
        EXPECT_EQ(common.mapPath, std::filesystem::path("/games/openarena/baseoa/maps/my map.bsp"));
        return "";
    } catch (const q3::cli::UsageError& e) {
        return e.what();
    }
}

// The preset's short label: the first "(...)" of its name, "(final + SH grid)".
std::string labelOf(const std::string& buildName) {
    size_t open = buildName.find('('), close = buildName.find(')');
    return open == std::string::npos || close == std::string::npos ? buildName
                                                                    : buildName.substr(open, close - open + 1);
}

// Per preset label, the switches the parser refused as not in this build yet.
std::map<std::string, std::set<std::string>> missingPerPreset(const BuildMenu& menu) {
    std::map<std::string, std::set<std::string>> missing;
    for (const BuildEntry& b : menu.builds) {
        std::set<std::string>& set = missing[labelOf(b.name)];
        for (const std::string& command : b.commands) {
            std::vector<std::string> words = shellWords(expand(command, menu));
            EXPECT_FALSE(words.empty()) << command;
            if (words.empty()) continue;
            EXPECT_EQ(words.front(), "/opt/netradiant/q3map2.x86_64");
            std::vector<std::string> args(words.begin() + 1, words.end());
            for (std::string error = parseLikeMain(args); !error.empty(); error = parseLikeMain(args)) {
                // Only "not in this build yet" is acceptable: never an unknown option or a bad value.
                bool stageNotYet = endsWith(error, kNotYet), optionNotYet = endsWith(error, kOptionNotYet);
                EXPECT_TRUE(stageNotYet || optionNotYet) << b.name << ": " << command << "\n  -> " << error;
                if (!stageNotYet && !optionNotYet) break;
                std::string name = error.substr(0, error.find(' '));
                set.insert(name);
                if (stageNotYet) break;
                // Drop the refused option and its values, and parse again for the next one.
                auto at = std::find(args.begin(), args.end(), name);
                EXPECT_NE(at, args.end()) << name;
                if (at == args.end()) break;
                auto next = at + 1;
                while (next + 1 < args.end() && (*next)[0] != '-') ++next;
                args.erase(at, next);
            }
        }
    }
    return missing;
}

// The README's table "What each preset needs today": label -> the backquoted switches of its last
// column.
std::map<std::string, std::set<std::string>> readmeMissing() {
    std::ifstream in(kDocs / "README.md");
    EXPECT_TRUE(in) << "cannot read " << kDocs / "README.md";
    std::map<std::string, std::set<std::string>> table;
    bool inSection = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("## ", 0) == 0) inSection = line == "## What each preset needs today";
        if (!inSection || line.rfind("| (", 0) != 0) continue;
        std::string label = line.substr(2, line.find(" |", 2) - 2);
        std::string last = line.substr(line.rfind('|', line.size() - 2));
        std::set<std::string>& set = table[label];
        for (size_t open = last.find('`'); open != std::string::npos; open = last.find('`', open + 1)) {
            size_t close = last.find('`', open + 1);
            if (close == std::string::npos) break;
            set.insert(last.substr(open + 1, close - open - 1));
            open = close;
        }
    }
    return table;
}

TEST(NetRadiantBuildMenu, HasNetRadiantLayoutAndTheQ3map2Variable) {
    BuildMenu menu = readMenu();
    EXPECT_EQ(menu.version, "2.0");
    ASSERT_EQ(menu.vars.size(), 1u);
    EXPECT_EQ(menu.vars[0].first, "q3map2");
    const std::string& q3map2 = menu.vars[0].second;
    EXPECT_EQ(q3map2.rfind("\"[RadiantPath]q3map2.[ExecutableType]\"", 0), 0u) << q3map2;
    EXPECT_NE(q3map2.find(" -connect [MonitorAddress]"), std::string::npos) << q3map2;
    EXPECT_NE(q3map2.find("-fs_basepath \"[EnginePath]\""), std::string::npos) << q3map2;
}

TEST(NetRadiantBuildMenu, OffersThePresets) {
    BuildMenu menu = readMenu();
    std::map<std::string, const BuildEntry*> byLabel;
    for (const BuildEntry& b : menu.builds) {
        EXPECT_FALSE(b.commands.empty()) << b.name;
        EXPECT_TRUE(byLabel.emplace(labelOf(b.name), &b).second) << "duplicate preset " << b.name;
    }
    auto lightLine = [&](const std::string& label) -> std::string {
        auto it = byLabel.find(label);
        if (it == byLabel.end()) return "<no preset " + label + ">";
        for (const std::string& c : it->second->commands)
            if (c.find(" -light ") != std::string::npos) return c;
        return "<no -light command in " + label + ">";
    };
    EXPECT_EQ(lightLine("(test)"), "[q3map2] -light -fast \"[MapFile]\"");
    EXPECT_EQ(lightLine("(final)"), "[q3map2] -light -fast -super 2 -filter -patchshadows \"[MapFile]\"");
    EXPECT_EQ(lightLine("(final + SH grid)"),
              "[q3map2] -light -fast -super 2 -filter -patchshadows -sh \"[MapFile]\"");
    EXPECT_EQ(lightLine("(final + SH grid + bounce)"),
              "[q3map2] -light -fast -super 2 -filter -patchshadows -sh -bounce 2 -bouncegrid \"[MapFile]\"");
    // The full presets run the three stages in order.
    for (const char* label : {"(test)", "(final)", "(final + SH grid)", "(final + SH grid + bounce)"}) {
        ASSERT_TRUE(byLabel.count(label)) << label;
        const std::vector<std::string>& commands = byLabel[label]->commands;
        ASSERT_EQ(commands.size(), 3u) << label;
        EXPECT_EQ(commands[0].rfind("[q3map2] -bsp ", 0), 0u) << label;
        EXPECT_EQ(commands[1].rfind("[q3map2] -vis ", 0), 0u) << label;
        EXPECT_EQ(commands[2].rfind("[q3map2] -light ", 0), 0u) << label;
    }
}

TEST(NetRadiantBuildMenu, EveryCommandLineIsWellShaped) {
    BuildMenu menu = readMenu();
    size_t lines = 0;
    for (const BuildEntry& b : menu.builds) {
        for (const std::string& line : b.commands) {
            ++lines;
            EXPECT_EQ(line.rfind("[q3map2] ", 0), 0u) << "does not start with the q3map2 variable: " << line;
            EXPECT_TRUE(endsWith(line, " \"[MapFile]\"")) << "map variable is not last: " << line;
            EXPECT_EQ(line.find('\n'), std::string::npos) << line;
        }
    }
    EXPECT_GE(lines, 13u);
}

TEST(NetRadiantBuildMenu, EveryCommandLineParsesOrIsRefusedAsNotYetImplemented) {
    BuildMenu menu = readMenu();
    std::map<std::string, std::set<std::string>> missing = missingPerPreset(menu);
    // Every stage and option of the presets is in this build: -bsp -meta, -vis, -light.
    for (const char* label : {"(test)", "(final)", "(final + SH grid)", "(final + SH grid + bounce)", "(single)",
                              "(relight final + SH grid)"}) {
        ASSERT_TRUE(missing.count(label)) << "no preset " << label;
        for (const std::string& s : missing[label]) ADD_FAILURE() << label << " needs " << s;
    }
}

TEST(NetRadiantBuildMenu, ReadmeSaysWhatEachPresetNeedsToday) {
    BuildMenu menu = readMenu();
    std::map<std::string, std::set<std::string>> fromParser = missingPerPreset(menu);
    std::map<std::string, std::set<std::string>> fromReadme = readmeMissing();
    EXPECT_EQ(fromReadme.size(), fromParser.size()) << "one README row per preset";
    for (const auto& [label, switches] : fromParser) {
        ASSERT_TRUE(fromReadme.count(label)) << "README has no row for " << label;
        EXPECT_EQ(fromReadme[label], switches) << "README row " << label;
    }
}

}  // namespace
