// docs/netradiant/build_menu.xml: well-formed, in NetRadiant's build-menu layout (<project
// version="2.0"> with <var> and <build name> holding <command>s), with the presets the docs promise.
// Every command line is written, one per line, to Q3MAP_BUILD_MENU_COMMANDS for the command-line
// parser tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <set>
#include <string>
#include <vector>

namespace {

const std::filesystem::path kMenuPath = std::filesystem::path(Q3MAP_SOURCE_DIR) / "docs/netradiant/build_menu.xml";

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
    xmlDocPtr doc = xmlReadFile(kMenuPath.c_str(), nullptr, XML_PARSE_NONET);
    EXPECT_NE(doc, nullptr) << kMenuPath << " is not well-formed XML";
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
    std::set<std::string> names;
    std::vector<std::string> lightLines;
    for (const BuildEntry& b : menu.builds) {
        EXPECT_FALSE(b.name.empty());
        EXPECT_TRUE(names.insert(b.name).second) << "duplicate preset " << b.name;
        EXPECT_FALSE(b.commands.empty()) << b.name;
        for (const std::string& c : b.commands)
            if (c.find(" -light ") != std::string::npos) lightLines.push_back(c);
    }
    auto hasLight = [&](const std::string& options, bool exact) {
        for (const std::string& line : lightLines) {
            std::string expected = "[q3map2] -light " + options + " \"[MapFile]\"";
            if (exact ? line == expected : line.find(options) != std::string::npos) return true;
        }
        return false;
    };
    EXPECT_TRUE(hasLight("-fast", true));                           // test
    EXPECT_TRUE(hasLight("-fast -super 2 -filter -patchshadows", true));  // final
    EXPECT_TRUE(hasLight("-fast -super 2 -filter -patchshadows -sh", true));  // final + SH
    EXPECT_TRUE(hasLight("-sh -bounce 2 -bouncegrid", false));      // final + SH + bounce
    // The test preset runs the three stages in order.
    ASSERT_FALSE(menu.builds.empty());
    const BuildEntry& test = menu.builds.front();
    ASSERT_EQ(test.commands.size(), 3u);
    EXPECT_NE(test.commands[0].find(" -bsp "), std::string::npos);
    EXPECT_NE(test.commands[1].find(" -vis "), std::string::npos);
    EXPECT_NE(test.commands[2].find(" -light -fast "), std::string::npos);
}

TEST(NetRadiantBuildMenu, ExtractsEveryCommandLine) {
    BuildMenu menu = readMenu();
    std::vector<std::string> lines;
    for (const BuildEntry& b : menu.builds)
        for (const std::string& c : b.commands) lines.push_back(c);
    ASSERT_GE(lines.size(), 10u);
    for (const std::string& line : lines) {
        EXPECT_EQ(line.rfind("[q3map2] ", 0), 0u) << "does not start with the q3map2 variable: " << line;
        EXPECT_TRUE(endsWith(line, " \"[MapFile]\"")) << "map variable is not last: " << line;
        EXPECT_EQ(line.find('\n'), std::string::npos) << line;
        // One stage switch per line, right after the executable.
        std::string afterExe = line.substr(std::string("[q3map2] ").size());
        EXPECT_TRUE(afterExe.rfind("-bsp ", 0) == 0 || afterExe.rfind("-vis ", 0) == 0 ||
                    afterExe.rfind("-light ", 0) == 0)
            << line;
    }

    std::filesystem::path out = Q3MAP_BUILD_MENU_COMMANDS;
    {
        std::ofstream file(out, std::ios::trunc);
        ASSERT_TRUE(file) << "cannot write " << out;
        for (const std::string& line : lines) file << line << '\n';
    }
    std::ifstream back(out);
    std::vector<std::string> reread;
    for (std::string line; std::getline(back, line);) reread.push_back(line);
    EXPECT_EQ(reread, lines);
}

}  // namespace
