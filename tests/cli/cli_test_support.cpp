#include "cli_test_support.h"

#include "common_option_table.h"

namespace q3::test {

std::vector<cli::StageDescription> testStages() {
    std::vector<cli::StageDescription> stages = cli::q3map2Stages();
    for (cli::StageDescription& s : stages) {
        if (s.name == "-info") s.available = true;
        if (s.name == "-light") {
            s.available = true;
            s.options = cli::describe(light::lightOptionTable());
        }
    }
    return stages;
}

light::LightOptions parseLight(const std::vector<std::string>& args) {
    std::vector<cli::StageDescription> stages = testStages();
    light::LightOptions options;
    cli::parseOptions(light::lightOptionTable(), args,
                      cli::stageParseContext("-light", cli::commonOptionTable(), stages), options);
    return options;
}

cli::CommandLine split(const std::vector<std::string>& args, CommonOptions* common) {
    CommonOptions local;
    std::vector<cli::StageDescription> stages = testStages();
    return cli::splitCommandLine(args, cli::commonOptionTable(), stages, common ? *common : local);
}

std::string usageErrorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const cli::UsageError& e) {
        return e.what();
    }
    return "<no error>";
}

}  // namespace q3::test
