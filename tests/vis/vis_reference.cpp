#include "vis_reference.h"

#include "conformance_pipeline.h"
#include "file_io.h"
#include "test_data.h"

#include <unistd.h>

#include <random>
#include <stdexcept>

namespace q3::vis::test {
namespace fs = std::filesystem;

namespace {

std::string referenceCommand(const fs::path& reference) {
    return q3::test::shellQuote(reference) + " -game quake3 -fs_basepath " +
           q3::test::shellQuote(q3::test::openArenaBase()) + " -fs_basegame baseoa -threads 2";
}

std::string runReference(const std::string& what, const std::string& commandLine) {
    std::string output;
    if (q3::test::runCommand(commandLine, &output) != 0)
        throw std::runtime_error(what + " failed: " + output.substr(output.size() > 600 ? output.size() - 600 : 0));
    return output;
}

std::string uniqueSuffix() {
    std::random_device entropy;
    return std::to_string(::getpid()) + "-" + std::to_string(entropy());
}

// Runs the reference's -vis `options` on a copy of the cached inputs and moves the BSP to `target`.
void referenceVis(const fs::path& reference, const VisReference& ref, const std::string& options, const fs::path& target) {
    const fs::path work = target.parent_path() / (".tmp-vis-" + uniqueSuffix());
    fs::create_directories(work);
    const fs::path bsp = work / ref.bsp.filename();
    fs::copy_file(ref.bsp, bsp);
    fs::copy_file(ref.prt, work / ref.prt.filename());
    try {
        const std::string output =
            runReference("reference -vis " + options + " on " + bsp.string(),
                         referenceCommand(reference) + " -vis " + options + " -saveprt " + q3::test::shellQuote(bsp));
        writeFileAtomic(fs::path(target).replace_extension(".log"), output);
        fs::rename(bsp, target);
    } catch (...) {
        fs::remove_all(work);
        throw;
    }
    fs::remove_all(work);
}

}  // namespace

VisReference visReference(const fs::path& reference, const std::string& mapName, bool withFull) {
    fs::path source;
    for (const fs::path& p : q3::test::oacmpMapSources())
        if (p.stem() == mapName) source = p;
    if (source.empty()) throw std::runtime_error("no .map source named " + mapName);
    const fs::path root = q3::test::dataCache() / "vis";
    const fs::path dir = root / conformance::freshCacheKey(reference, source);
    VisReference ref{dir / (mapName + ".bsp"), dir / (mapName + ".prt"), dir / (mapName + ".fast.bsp"),
                     dir / (mapName + ".full.bsp")};
    if (!fs::exists(ref.prt)) {
        const fs::path work = root / (".tmp-" + mapName + "-" + uniqueSuffix());
        fs::create_directories(work / "maps");
        const fs::path map = work / "maps" / (mapName + ".map");
        fs::copy_file(source, map);
        try {
            runReference("reference -bsp -meta on " + source.string(),
                         "cd " + q3::test::shellQuote(work) + " && " + referenceCommand(reference) + " -bsp -meta " +
                             q3::test::shellQuote(map));
            for (const char* ext : {".bsp", ".prt"}) fs::rename(work / "maps" / (mapName + ext), work / (mapName + ext));
            fs::remove_all(work / "maps");
        } catch (...) {
            fs::remove_all(work);
            throw;
        }
        std::error_code ec;
        fs::rename(work, dir, ec);
        if (ec) fs::remove_all(work);  // another process put its compile there first
        if (!fs::exists(ref.prt)) throw std::runtime_error(dir.string() + ": the reference compile is missing");
    }
    if (!fs::exists(ref.fastBsp)) referenceVis(reference, ref, "-fast", ref.fastBsp);
    if (withFull && !fs::exists(ref.fullBsp)) referenceVis(reference, ref, "", ref.fullBsp);
    return ref;
}

fs::path referenceVisWith(const fs::path& reference, const VisReference& ref, const std::string& option) {
    const fs::path target = ref.bsp.parent_path() / (ref.bsp.stem().string() + option + ".bsp");
    if (!fs::exists(target)) referenceVis(reference, ref, option, target);
    return target;
}

fs::path stageVisInputs(const VisReference& ref, const fs::path& dir) {
    fs::create_directories(dir);
    fs::copy_file(ref.bsp, dir / ref.bsp.filename(), fs::copy_options::overwrite_existing);
    fs::copy_file(ref.prt, dir / ref.prt.filename(), fs::copy_options::overwrite_existing);
    return dir / ref.bsp.filename();
}

int runOurVis(const fs::path& bsp, const std::string& options, int threads, std::string* log) {
    return q3::test::runCommand(q3::test::shellQuote(q3::test::q3map2Exe()) + " -threads " + std::to_string(threads) +
                                    " -vis " + options + " " + q3::test::shellQuote(bsp),
                                log);
}

}  // namespace q3::vis::test
