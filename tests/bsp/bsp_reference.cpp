#include "bsp_reference.h"

#include <unistd.h>

#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "bsp_samples.h"
#include "bsp_stage.h"
#include "bspfile.h"
#include "conformance_pipeline.h"
#include "file_io.h"
#include "log.h"
#include "shader_loader.h"
#include "test_data.h"
#include "vfs.h"

namespace q3::bspstage::test {

namespace fs = std::filesystem;
using namespace q3::test;

fs::path ourCompile(const fs::path& mapSource, const fs::path& work, const BspOptions& options, std::string* log) {
    fs::remove_all(work);
    fs::create_directories(work / "maps");
    const fs::path map = work / "maps" / mapSource.filename();
    fs::copy_file(mapSource, map);
    CommonOptions common;
    common.basePaths.push_back(openArenaBase().string());
    common.baseGame = "baseoa";
    common.mapPath = fs::path(map).replace_extension(".bsp");
    common.commandLine = "-bsp";
    Log out(false);
    out.setVerbose(log != nullptr);
    if (log) out.addSink([log](LogLevel, std::string_view text) { log->append(text).append("\n"); });
    runBspStage(options, common, out);
    return common.mapPath;
}

fs::path referenceCompile(const fs::path& reference, const fs::path& mapSource, const std::string& extraOptions,
                          bool meta) {
    const std::string name = mapSource.stem().string();
    const fs::path root = dataCache() / "bsp-prt";
    std::string key = conformance::freshCacheKey(reference, mapSource);
    if (!meta) key += "-plain";
    for (char c : extraOptions) key += c == ' ' ? '_' : c;
    const fs::path final = root / key;
    // -autocaulk stops before the BSP: its .caulk stands for it.
    if (fs::exists(final / (name + ".log")) &&
        (fs::exists(final / (name + ".bsp")) || fs::exists(final / (name + ".caulk"))))
        return final;
    fs::remove_all(final);  // an older, incomplete entry
    std::random_device entropy;
    const fs::path work = root / (".tmp-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(entropy()));
    fs::create_directories(work / "maps");
    fs::copy_file(mapSource, work / "maps" / (name + ".map"));
    const std::string command = "cd " + shellQuote(work) + " && " + shellQuote(reference) +
                                " -v -threads 2 -game quake3 -fs_basepath " + shellQuote(openArenaBase()) +
                                " -fs_basegame baseoa -bsp " + (meta ? "-meta " : "") + extraOptions + " " +
                                shellQuote("maps/" + name + ".map");
    std::string output;
    const int status = runCommand(command, &output);
    if (status != 0) {
        fs::remove_all(work);
        throw std::runtime_error("reference -bsp failed on " + mapSource.string() + ": " + output.substr(0, 400));
    }
    fs::create_directories(work / "keep");
    for (const char* ext : {".prt", ".lin", ".bsp", ".srf", ".caulk"})
        if (fs::exists(work / "maps" / (name + ext))) fs::rename(work / "maps" / (name + ext), work / "keep" / (name + ext));
    writeFileAtomic(work / "keep" / (name + ".log"), output);
    fs::remove_all(work / "maps");
    std::error_code ec;
    fs::rename(work / "keep", final, ec);  // another process may have put its copy there first
    fs::remove_all(work);
    return final;
}

fs::path referenceSampleCompile(const fs::path& reference, const std::string& name, const fs::path& work,
                                const std::vector<std::string>& extraOptions) {
    return referenceSampleCompileWith(reference, name, sampleOptionsWith(name, extraOptions), work);
}

fs::path referenceSampleCompileWith(const fs::path& reference, const std::string& name,
                                    const std::vector<std::string>& args, const fs::path& work) {
    fs::remove_all(work);
    fs::create_directories(work);
    fs::copy(samplesRoot() / "samples", work / "samples", fs::copy_options::recursive);
    std::string options;
    for (const std::string& arg : args) options += " " + shellQuote(arg);
    std::string output;
    const int status = runCommand(shellQuote(reference) + " -threads 1 -game quake3 -fs_basepath " + shellQuote(work) +
                                      " -fs_basegame samples -bsp" + options + " " +
                                      shellQuote(work / "samples/maps" / (name + ".map")),
                                  &output);
    EXPECT_EQ(status, 0) << output;
    return work / "samples/maps";
}

SampleCompiles compileSampleBothWays(const fs::path& reference, const std::string& name,
                                     const std::vector<std::string>& extraOptions) {
    return compileSampleBothWaysWith(reference, name, sampleOptionsWith(name, extraOptions));
}

SampleCompiles compileSampleBothWaysWith(const fs::path& reference, const std::string& name,
                                         const std::vector<std::string>& args) {
    SampleCompiles out;
    out.work = q3::test::tempDir() / (name + "-" + std::to_string(::getpid()));
    out.ours = compileSampleWith(name, args, out.work / "ours");
    out.theirs = referenceSampleCompileWith(reference, name, args, out.work / "ref");
    return out;
}

void expectSampleOutputsEqual(const SampleCompiles& compiles, const std::string& name) {
    const bsp::Bsp a = bsp::readBsp(compiles.ours / (name + ".bsp")), b = bsp::readBsp(compiles.theirs / (name + ".bsp"));
    for (int lump = 0; lump < bsp::kMaxLumps; ++lump) {
        if (lump == bsp::LUMP_ENTITIES) continue;
        EXPECT_TRUE(bsp::lumpBytes(a, lump) == bsp::lumpBytes(b, lump)) << bsp::lumpName(lump);
    }
    // A leaking map writes a .lin instead of a .prt: whichever the reference wrote must match.
    for (const char* extension : {".srf", ".prt", ".lin"}) {
        const bool theirs = fs::exists(compiles.theirs / (name + extension));
        EXPECT_EQ(fs::exists(compiles.ours / (name + extension)), theirs) << extension;
        if (theirs && fs::exists(compiles.ours / (name + extension))) {
            EXPECT_EQ(readFileText(compiles.ours / (name + extension)), readFileText(compiles.theirs / (name + extension)))
                << extension;
        }
    }
}

fs::path oacmpSource(const std::string& name) {
    for (const fs::path& p : oacmpMapSources())
        if (p.stem() == name) return p;
    ADD_FAILURE() << name << ".map is not among the oacmp sources";
    return {};
}

const ShaderTable& openArenaShaders() {
    static Log log(false);
    static const ShaderTable table = [] {
        VfsOptions options;
        options.basePaths.push_back(openArenaBase());
        options.baseGame = "baseoa";
        Vfs vfs(options, log);
        return loadShaderTable(vfs, log);
    }();
    return table;
}

}  // namespace q3::bspstage::test
