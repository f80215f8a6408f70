// docs/user-guide.md covers every stage of this build and every option it implements: each stage
// has a "### `-stage" section, and each implemented option (common or of a stage) is named in
// backquotes by at least one of its names. An option added to a table without documentation fails.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "bsp_options.h"
#include "common_option_table.h"
#include "info_stage.h"
#include "json_stage.h"
#include "light_options.h"
#include "lightmap_export.h"
#include "sh_tools.h"
#include "vis_stage.h"

namespace q3::test {
namespace {

std::string userGuide() {
    std::ifstream in(std::filesystem::path(Q3MAP_SOURCE_DIR) / "docs/user-guide.md");
    EXPECT_TRUE(in) << "cannot read docs/user-guide.md";
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// "`-name" followed by the end of the quoted text, a blank or a comma: "-v" is not found in "`-vis`".
bool mentions(const std::string& guide, const std::string& name) {
    const std::string needle = "`" + name;
    for (size_t at = guide.find(needle); at != std::string::npos; at = guide.find(needle, at + 1)) {
        char next = at + needle.size() < guide.size() ? guide[at + needle.size()] : '`';
        if (next == '`' || next == ' ' || next == ',' || next == '|') return true;
    }
    return false;
}

void expectDocumented(const std::vector<cli::OptionInfo>& options, const std::string& table) {
    const std::string guide = userGuide();
    for (const cli::OptionInfo& option : options) {
        if (!option.implemented) continue;
        bool found = false;
        for (const std::string& name : option.names) found = found || mentions(guide, name);
        EXPECT_TRUE(found) << table << " option " << option.name() << " is not in docs/user-guide.md";
    }
}

TEST(DocsReference, EveryImplementedOptionIsInTheUserGuide) {
    expectDocumented(cli::describe(cli::commonOptionTable()), "common");
    expectDocumented(cli::describe(info::infoOptionTable()), "-info");
    expectDocumented(cli::describe(light::lightOptionTable()), "-light");
    expectDocumented(cli::describe(json::jsonOptionTable()), "-json");
    expectDocumented(cli::describe(shtools::shProbeOptionTable()), "-shprobe");
    expectDocumented(cli::describe(shtools::shImageOptionTable()), "-shimage");
    expectDocumented(cli::describe(shtools::shCubemapOptionTable()), "-shcubemap");
    expectDocumented(cli::describe(light::pictureStageOptionTable()), "-export/-import");
    expectDocumented(cli::describe(vis::visOptionTable()), "-vis");
    expectDocumented(cli::describe(bspstage::bspOptionTable()), "-bsp");
}

TEST(DocsReference, EveryStageOfThisBuildHasASection) {
    std::vector<std::string> headings;
    std::istringstream in(userGuide());
    for (std::string line; std::getline(in, line);)
        if (line.rfind("### ", 0) == 0) headings.push_back(line);
    for (const char* stage : {"-bsp", "-info", "-vis", "-light", "-json", "-shprobe", "-shimage", "-shcubemap", "-export", "-import"}) {
        bool found = false;
        for (const std::string& heading : headings) found = found || mentions(heading, stage);
        EXPECT_TRUE(found) << "no ### heading names `" << stage << "`";
    }
}

TEST(DocsReference, MentionsIsExact) {
    EXPECT_TRUE(mentions("use `-v` or", "-v"));
    EXPECT_TRUE(mentions("`-samples N`", "-samples"));
    EXPECT_TRUE(mentions("`-fast`, `-faster`", "-fast"));
    EXPECT_FALSE(mentions("`-vis`", "-v"));
    EXPECT_FALSE(mentions("-v without quotes", "-v"));
}

}  // namespace
}  // namespace q3::test
