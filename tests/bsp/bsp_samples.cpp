#include "bsp_samples.h"

#include <algorithm>

#include "bsp_stage.h"
#include "log.h"

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

fs::path compileSample(const std::string& name, const fs::path& work) {
    fs::remove_all(work);
    fs::create_directories(work);
    fs::copy(samplesRoot() / "samples", work / "samples", fs::copy_options::recursive);
    CommonOptions common;
    common.basePaths.push_back(work.string());
    common.baseGame = "samples";
    common.mapPath = work / "samples" / "maps" / (name + ".bsp");
    common.commandLine = "-bsp";
    Log log(false);
    runBspStage(BspOptions{}, common, log);
    return work / "samples" / "maps";
}

}  // namespace q3::bspstage::test
