#include "bsp_samples.h"

#include <algorithm>
#include <sstream>

#include "bsp_options.h"
#include "bsp_stage.h"
#include "file_io.h"
#include "log.h"
#include "option_parser.h"

namespace q3::bspstage::test {

namespace fs = std::filesystem;

fs::path samplesRoot() { return fs::path(Q3MAP_SOURCE_DIR) / "bsp-samples"; }
fs::path goldenDir() { return samplesRoot() / "golden"; }

std::vector<std::string> sampleNames() {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(samplesRoot() / "samples" / "maps"))
        if (e.path().extension() == ".map") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::string> sampleOutputExtensions(const fs::path& dir, const std::string& name) {
    std::vector<std::string> out;
    for (const char* ext : {".bsp", ".srf", ".prt", ".lin"})
        if (fs::exists(dir / (name + ext))) out.push_back(ext);
    return out;
}

std::vector<std::string> sampleOptions(const std::string& name) {
    const std::string text = readFileText(samplesRoot() / "samples" / "maps" / (name + ".map"));
    const std::string prefix = "// options:";
    std::vector<std::string> args;
    if (text.compare(0, prefix.size(), prefix) != 0) return args;
    std::istringstream line(text.substr(prefix.size(), text.find('\n') - prefix.size()));
    for (std::string arg; line >> arg;) args.push_back(arg);
    return args;
}

std::vector<std::string> sampleOptionsWith(const std::string& name, const std::vector<std::string>& extraOptions) {
    std::vector<std::string> args = sampleOptions(name);
    args.insert(args.end(), extraOptions.begin(), extraOptions.end());
    return args;
}

fs::path compileSample(const std::string& name, const fs::path& work, Log* log,
                       const std::vector<std::string>& extraOptions) {
    return compileSampleWith(name, sampleOptionsWith(name, extraOptions), work, log);
}

fs::path compileSampleWith(const std::string& name, const std::vector<std::string>& args, const fs::path& work,
                           Log* log) {
    fs::remove_all(work);
    fs::create_directories(work);
    fs::copy(samplesRoot() / "samples", work / "samples", fs::copy_options::recursive);
    CommonOptions common;
    common.basePaths.push_back(work.string());
    common.baseGame = "samples";
    common.mapPath = work / "samples" / "maps" / (name + ".bsp");
    common.commandLine = "-bsp";
    for (const std::string& arg : args) common.commandLine += " " + arg;
    BspOptions options;
    cli::parseOptions(bspOptionTable(), args, cli::ParseContext{}, options);
    Log quiet(false);
    runBspStage(options, common, log ? *log : quiet);
    return work / "samples" / "maps";
}

}  // namespace q3::bspstage::test
