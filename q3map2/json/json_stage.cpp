#include "json_stage.h"

#include "json_error.h"

#include <chrono>

namespace q3::json {
namespace fs = std::filesystem;

namespace {

fs::path bspPathOf(const fs::path& mapPath) {
    fs::path p = mapPath;
    p.replace_extension(".bsp");
    return p;
}

}  // namespace

int runJsonStage(const JsonOptions& options, const CommonOptions& common, Log& log) {
    if (options.unpack == options.pack) throw CompileError("-json needs exactly one of -unpack and -pack");
    fs::path bspPath = bspPathOf(common.mapPath);
    fs::path folder = fs::path(bspPath).replace_extension("");
    auto start = std::chrono::steady_clock::now();
    if (options.unpack) {
        log.info("Loading " + bspPath.string());
        bsp::ReadOptions readOptions;
        readOptions.force = common.force;
        bsp::Bsp bsp = bsp::readBsp(bspPath, readOptions);
        unpackBsp(bsp, folder, options, log);
    } else {
        bsp::Bsp bsp = packFolder(folder, options, log);
        fs::path out = folder.string() + "_json.bsp";
        log.info("Writing " + out.string());
        bsp::writeBsp(out, bsp);
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%9.2f seconds elapsed", seconds);
    log.info(buf);
    return 0;
}

}  // namespace q3::json
