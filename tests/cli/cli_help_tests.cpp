// The -help text: every table entry listed with its default, and the text and the parser agree
// (each option the help lists parses with the number of values the help shows).
#include "cli_test_support.h"
#include "common_option_table.h"

#include <gtest/gtest.h>

#include <sstream>

namespace q3::test {
namespace {

struct HelpEntry {
    std::vector<std::string> names;
    size_t requiredValues = 0;
    size_t optionalValues = 0;
    std::string text;  // the entry's whole text, whitespace collapsed
};

std::string collapse(const std::string& text) {
    std::istringstream in(text);
    std::string out;
    for (std::string w; in >> w;) out += (out.empty() ? "" : " ") + w;
    return out;
}

// Entries of the section that starts with the line `heading`, read back from the text alone.
std::vector<HelpEntry> entriesOf(const std::string& help, const std::string& heading) {
    std::istringstream in(help);
    std::vector<HelpEntry> entries;
    bool inSection = false;
    std::string block;
    auto finish = [&] {
        if (block.empty()) return;
        HelpEntry e;
        e.text = collapse(block);
        std::istringstream words(e.text);
        for (std::string w; words >> w;) {
            if (w.back() == ',') w.pop_back();
            // Aliases repeat the placeholders; count those of the first name only.
            if (w[0] == '-') e.names.push_back(w);
            else if (w[0] == '<') e.requiredValues += e.names.size() == 1;
            else if (w.rfind("[<", 0) == 0) e.optionalValues += e.names.size() == 1;
            else break;
        }
        entries.push_back(e);
        block.clear();
    };
    for (std::string line; std::getline(in, line);) {
        if (line == heading) {
            inSection = true;
            continue;
        }
        if (!inSection) continue;
        if (line.empty() || line[0] != ' ') break;
        if (line.rfind("  -", 0) == 0) {
            finish();
            block = line;
        } else {
            block += " " + line;
        }
    }
    finish();
    return entries;
}

std::string exampleValue(const cli::ArgSpec& spec, const cli::OptionInfo& option) {
    if (spec.kind == cli::ArgKind::Text) return option.defaultText != "none" ? option.defaultText : "value";
    const cli::Range& r = spec.range;
    double v = 1;
    if (r.min) v = r.minExclusive ? *r.min + 1 : *r.min;
    else if (r.max) v = r.maxExclusive ? *r.max - 1 : *r.max;
    return cli::formatNumber(v);
}

const HelpEntry* findEntry(const std::vector<HelpEntry>& entries, const std::string& name) {
    for (const HelpEntry& e : entries)
        if (std::find(e.names.begin(), e.names.end(), name) != e.names.end()) return &e;
    return nullptr;
}

std::string lightHelp() {
    std::vector<cli::StageDescription> stages = testStages();
    return cli::helpText(split({"-help", "light"}), cli::commonOptionTable(), stages);
}

std::string generalHelp() {
    std::vector<cli::StageDescription> stages = testStages();
    return cli::helpText(split({"-help"}), cli::commonOptionTable(), stages);
}

void expectEveryEntryListed(const std::vector<cli::OptionInfo>& table, const std::vector<HelpEntry>& entries) {
    EXPECT_EQ(entries.size(), table.size());
    for (const cli::OptionInfo& option : table) {
        const HelpEntry* entry = findEntry(entries, option.name());
        ASSERT_NE(entry, nullptr) << option.name() << " missing from the help";
        EXPECT_EQ(entry->names, option.names);
        EXPECT_NE(entry->text.find("(default: " + option.defaultText + ")"), std::string::npos)
            << option.name() << ": " << entry->text;
        EXPECT_EQ(entry->text.find("[not implemented yet]") != std::string::npos, !option.implemented)
            << option.name();
    }
}

TEST(CliHelp, LightHelpListsEveryEntryWithItsDefault) {
    std::vector<HelpEntry> entries = entriesOf(lightHelp(), "Light Stage:");
    ASSERT_FALSE(entries.empty());
    EXPECT_EQ(entries.front().names, (std::vector<std::string>{"-light"}));
    entries.erase(entries.begin());  // the stage switch itself
    expectEveryEntryListed(cli::describe(light::lightOptionTable()), entries);
    const HelpEntry* gridsh = findEntry(entries, "-gridsh");
    ASSERT_NE(gridsh, nullptr);
    EXPECT_EQ(gridsh->requiredValues, 3u);
    EXPECT_NE(gridsh->text.find("(default: derived from -gridscalesh)"), std::string::npos);
    EXPECT_NE(findEntry(entries, "-gridscalesh")->text.find("(default: 2)"), std::string::npos);
    EXPECT_NE(findEntry(entries, "-areascale")->text.find("(default: 0.25)"), std::string::npos);
    EXPECT_NE(findEntry(entries, "-pointscale")->text.find("(default: 7500)"), std::string::npos);
}

TEST(CliHelp, HelpTextAndParserAgree) {
    const auto& table = light::lightOptionTable();
    std::vector<cli::OptionInfo> infos = cli::describe(table);
    std::vector<HelpEntry> entries = entriesOf(lightHelp(), "Light Stage:");
    entries.erase(entries.begin());
    size_t parsedImplemented = 0, refused = 0;
    for (const HelpEntry& entry : entries) {
        for (const std::string& name : entry.names) {
            int index = cli::findOption(infos, name);
            ASSERT_GE(index, 0) << name << " is in the help but not in the table";
            const cli::OptionInfo& option = infos[static_cast<size_t>(index)];
            ASSERT_EQ(entry.requiredValues + entry.optionalValues, option.args.size()) << name;
            std::vector<std::string> args{name};
            for (size_t k = 0; k < entry.requiredValues; ++k) args.push_back(exampleValue(option.args[k], option));
            std::string error = usageErrorOf([&] { parseLight(args); });
            if (entry.text.find("[not implemented yet]") == std::string::npos) {
                EXPECT_EQ(error, "<no error>") << name;
                ++parsedImplemented;
            } else {
                EXPECT_EQ(error, name + " is a q3map2 option this build does not implement yet");
                ++refused;
            }
        }
    }
    size_t implementedNames = 0, refusedNames = 0;  // aliases included
    for (const cli::OptionInfo& option : infos)
        (option.implemented ? implementedNames : refusedNames) += option.names.size();
    EXPECT_EQ(parsedImplemented, implementedNames);
    EXPECT_EQ(refused, refusedNames);
}

TEST(CliHelp, GeneralHelpListsCommonOptionsAndStages) {
    std::string help = generalHelp();
    std::vector<HelpEntry> common = entriesOf(help, "Common Options:");
    expectEveryEntryListed(cli::describe(cli::commonOptionTable()), common);
    std::vector<HelpEntry> stages = entriesOf(help, "Stages:");
    std::vector<cli::StageDescription> expected = testStages();
    ASSERT_EQ(stages.size(), expected.size());
    for (size_t i = 0; i < stages.size(); ++i) {
        EXPECT_EQ(stages[i].names, (std::vector<std::string>{expected[i].name}));
        EXPECT_EQ(stages[i].text.find("[not implemented yet]") == std::string::npos, expected[i].available)
            << expected[i].name;
    }
    // Every common option the help shows parses (or is refused as not implemented) before a stage.
    for (const HelpEntry& entry : common) {
        const auto infos = cli::describe(cli::commonOptionTable());
        const cli::OptionInfo& option = infos[static_cast<size_t>(cli::findOption(infos, entry.names[0]))];
        std::vector<std::string> args{entry.names[0]};
        for (size_t k = 0; k < entry.requiredValues; ++k) args.push_back(exampleValue(option.args[k], option));
        args.insert(args.end(), {"-info", "m.bsp"});
        std::string error = usageErrorOf([&] { split(args); });
        if (option.implemented) EXPECT_EQ(error, "<no error>") << entry.names[0];
        else EXPECT_EQ(error, entry.names[0] + " is a q3map2 option this build does not implement yet");
    }
}

TEST(CliHelp, HelpLinesFitEightyColumnsWhenTheyCan) {
    std::istringstream in(lightHelp());
    for (std::string line; std::getline(in, line);) {
        if (line.size() <= 80) continue;
        // Only a long option head may overflow; the wrapped text never does.
        EXPECT_EQ(line.rfind("  -", 0), 0u) << line;
    }
}

TEST(CliHelp, GameList) {
    std::vector<cli::StageDescription> stages = testStages();
    EXPECT_EQ(cli::helpText(split({"-help", "game"}), cli::commonOptionTable(), stages),
              "Available games:\n  quake3\n  quakelive\n");
    // Every listed game is accepted by -game.
    for (const std::string& game : cli::supportedGames()) {
        CommonOptions common;
        split({"-game", game, "-info", "m.bsp"}, &common);
        EXPECT_EQ(common.game, game);
    }
}

TEST(CliHelp, UnknownHelpTopic) {
    std::vector<cli::StageDescription> stages = testStages();
    EXPECT_EQ(usageErrorOf([&] { cli::helpText(split({"-help", "ligth"}), cli::commonOptionTable(), stages); }),
              "no help for unknown stage 'ligth'; did you mean 'light'?");
    EXPECT_EQ(usageErrorOf([&] { cli::helpText(split({"-help", "qqqqqqqq"}), cli::commonOptionTable(), stages); }),
              "no help for unknown stage 'qqqqqqqq' (see q3map2 -help)");
}

}  // namespace
}  // namespace q3::test
