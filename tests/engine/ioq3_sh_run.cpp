#include "ioq3_sh_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "file_io.h"
#include "sh_grid_runtime_c.h"
#include "test_data.h"

namespace q3::enginetest {
namespace fs = std::filesystem;

fs::path patchedIoq3(std::string& why) {
    std::string output;
    const int status = test::runCommand(shellQuote(std::string(Q3MAP_IOQ3_SH_BUILD)), &output);
    // Exit 3: a prerequisite is missing (the script names it); anything else but 0 is a failed build.
    if (status == 3) {
        why = output;
        return {};
    }
    if (status != 0) {
        ADD_FAILURE() << Q3MAP_IOQ3_SH_BUILD << " exited with " << status << "\n" << output;
        throw std::runtime_error("the patched renderer did not build");
    }
    std::string last;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) last = line;
    return fs::path(last) / "ioquake3";
}

void runStage(const fs::path& gameDir, const std::vector<std::string>& stage, const std::string& file) {
    std::vector<std::string> words = {test::q3map2Exe().string(), "-fs_basepath", test::openArenaBase().string(),
                                      "-fs_game", "baseoa"};
    words.insert(words.end(), stage.begin(), stage.end());
    words.push_back(file);
    std::string command = "cd " + shellQuote(gameDir.string()) + " &&";
    for (const std::string& word : words) command.append(" ").append(shellQuote(word));
    std::string output;
    if (const int status = test::runCommand(command, &output); status != 0) {
        ADD_FAILURE() << command << " exited with " << status << "\n" << output;
        throw std::runtime_error("q3map2 failed");
    }
}

fs::path compileWithShBspx(const fs::path& gameDir, const std::string& name) {
    runStage(gameDir, {"-bsp", "-meta"}, "maps/" + name + ".map");
    runStage(gameDir, {"-vis", "-fast"}, "maps/" + name + ".bsp");
    runStage(gameDir, {"-light", "-fast", "-sh", "-shbspx"}, "maps/" + name + ".bsp");
    return gameDir / "maps" / (name + ".bsp");
}

Shot shootThird(const fs::path& ioq3, const fs::path& bsp, const std::string& view, GridChoice grid,
                const fs::path& dir, const std::vector<std::string>& extraLines, const std::string& settle) {
    const char* name = grid == GridChoice::Sh ? "sh" : grid == GridChoice::Legacy ? "legacy" : "nomodel";
    std::vector<std::string> options = {"-P", view, "-d", settle, "-x",
                                        grid == GridChoice::Sh       ? "ioq3:set r_shGrid 1"
                                        : grid == GridChoice::Legacy ? "ioq3:set r_shGrid 0"
                                                                     : "ioq3:set r_drawentities 0"};
    // No blob shadow: it darkens the floor around the feet, which the model mask would take in.
    options.insert(options.end(), {"-x", "ioq3:set cg_shadows 0"});
    // Every frame advances the game by the same 33 ms: the model's idle pose at the shot then
    // follows the frame count, not how fast the machine renders (a slow frame moved it on).
    options.insert(options.end(), {"-x", "ioq3:set fixedtime 33"});
    for (const std::string& line : extraLines) options.insert(options.end(), {"-x", "ioq3:" + line});
    const fs::path prefix = dir / name;
    const fs::path logDir = dir / (std::string(name) + "-logs");
    const RunResult r = runScreenshotWith(bsp, "ioq3", "third", prefix, logDir, options, ioq3);
    if (r.status != 0) {
        ADD_FAILURE() << r.command << " exited with " << r.status << "\n" << r.output;
        throw std::runtime_error("no screenshot");
    }
    Shot shot;
    shot.image = readPng(screenshotPath(prefix, "ioq3", "third"));
    shot.log = readFileText(logDir / (bsp.stem().string() + ".ioq3-client.log"));
    return shot;
}

MaskedStats modelStats(const Shot& withModel, const Shot& withoutModel) {
    // 24 levels: well above the software rasteriser's noise between runs, below any lit model.
    return maskedStats(withModel.image, differenceMask(withoutModel.image, withModel.image, 24));
}

std::vector<RendererSample> rendererSamples(const std::string& log) {
    std::vector<RendererSample> samples;
    for (const std::string& line : linesWith(log, "shgrid at ")) {
        RendererSample s{};
        std::istringstream in(line.substr(line.find("shgrid at ") + 10));
        std::string equals;
        in >> s.position[0] >> s.position[1] >> s.position[2] >> equals;
        for (float& c : s.coeffs) in >> c;
        if (in && equals == "=") samples.push_back(s);
    }
    return samples;
}

double largestRuntimeDifference(const fs::path& bsp, const RendererSample& sample) {
    const std::vector<uint8_t> bytes = readFileBytes(bsp);
    char error[256] = {};
    q3sh_grid* grid = q3sh_grid_load(bytes.data(), bytes.size(), error, sizeof error);
    if (!grid) throw std::runtime_error(std::string("the runtime rejects the grid: ") + error);
    float expected[27];
    q3sh_grid_sample(grid, sample.position, expected);
    const bool bspx = q3sh_grid_source(grid) == Q3SH_SOURCE_BSPX;
    q3sh_grid_free(grid);
    if (!bspx) throw std::runtime_error("the runtime found no BSPX LIGHTGRID_SH");
    double largest = 0;
    for (int i = 0; i < 27; ++i) largest = std::max(largest, double(std::abs(expected[i] - sample.coeffs[i])));
    return largest;
}

double gridSphereMean(const fs::path& bsp, const float position[3]) {
    const std::vector<uint8_t> bytes = readFileBytes(bsp);
    char error[256] = {};
    q3sh_grid* grid = q3sh_grid_load(bytes.data(), bytes.size(), error, sizeof error);
    if (!grid) throw std::runtime_error(std::string("the runtime rejects the grid: ") + error);
    float coeffs[27];
    q3sh_grid_sample(grid, position, coeffs);
    q3sh_grid_free(grid);
    // Coefficient 0 times Y_0 is the irradiance averaged over the sphere.
    constexpr double kY0 = 0.282094791773878;
    return kY0 * (coeffs[0] + coeffs[1] + coeffs[2]) / 3.0;
}

std::vector<double> frameTimes(const std::string& log, size_t skip) {
    std::vector<double> times;
    for (const std::string& line : linesWith(log, " all:")) {
        int frame = 0, all = 0;
        const size_t at = line.find("frame:");
        if (at != std::string::npos && std::sscanf(line.c_str() + at, "frame:%d all:%d", &frame, &all) == 2)
            times.push_back(all);
    }
    if (times.size() <= skip) return {};
    return {times.begin() + long(skip), times.end()};
}

}  // namespace q3::enginetest
